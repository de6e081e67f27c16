#include "master/dc.hpp"

#include <fmt/format.h>

#include <array>
#include <vector>

#include "master/master.hpp"
#include "master/registers.hpp"

namespace vdrive::master {

namespace {
std::uint64_t le64(std::span<const std::uint8_t> p) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8 && i < p.size(); ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}
std::uint32_t le32(std::span<const std::uint8_t> p) { return static_cast<std::uint32_t>(le64(p.first(4))); }
std::array<std::uint8_t, 8> bytes64(std::uint64_t v) {
  std::array<std::uint8_t, 8> b{};
  for (int i = 0; i < 8; ++i) b[i] = static_cast<std::uint8_t>(v >> (8 * i));
  return b;
}
void require(const Wkc& wkc, std::uint16_t expected, const char* what, std::size_t slave) {
  if (!wkc || *wkc != expected) throw MasterError(fmt::format("slave {}: {} not taken", slave, what));
}
}  // namespace

DcResult configure_dc(Master& master, const DcOptions& options) {
  Transport& t = master.transport();
  DcResult result;
  auto& slaves = master.slaves();
  // 1. Latch the receive times of one frame at every port of every slave.
  std::array<std::uint8_t, 4> latch{};
  if (!t.bwr(reg::kDcReceiveTimes, latch)) throw MasterError("BWR 0x0900 (DC receive time latch): no reply");

  struct Times {
    std::uint32_t port0 = 0, port1 = 0;
    bool port1_open = false;
    std::uint64_t local = 0;   // 0x0918: local time of the port-0 receive
  };
  std::vector<Times> times(slaves.size());
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    Slave& s = slaves[i];
    if (!s.dc_supported) continue;
    std::array<std::uint8_t, 16> ports{};
    std::array<std::uint8_t, 8> local{};
    require(t.fprd(s.station, reg::kDcReceiveTimes, ports), 1, "FPRD DC receive times", i);
    require(t.fprd(s.station, reg::kDcReceiveTimeUnit, local), 1, "FPRD DC receive time unit", i);
    const auto dl = t.fprd_value<std::uint16_t>(s.station, reg::kDlStatus).value_or(0);
    times[i] = {le32(std::span(ports).subspan(0, 4)), le32(std::span(ports).subspan(4, 4)),
                (dl & reg::kDlStatusPort1Comm) != 0, le64(local)};
  }

  // 2./3. Delays along the line, offsets to the reference's time base.
  std::size_t ref = slaves.size();
  std::int64_t prev_rt = 0, prev_delay = 0;
  std::uint64_t ref_local = 0;
  std::int64_t ref_offset = 0;
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    Slave& s = slaves[i];
    if (!s.dc_supported) continue;
    // 32-bit port times wrap: the unsigned difference is right as long as the round trip is short.
    const std::int64_t rt = times[i].port1_open ? static_cast<std::int64_t>(static_cast<std::uint32_t>(times[i].port1 - times[i].port0)) : 0;
    if (ref == slaves.size()) {
      ref = i;
      ref_local = times[i].local;
      // The reference clock starts at the master's time.
      ref_offset = static_cast<std::int64_t>(static_cast<std::uint64_t>(master.clock().now()) - ref_local);
      s.dc_delay = 0;
      s.dc_offset = ref_offset;
      result.reference_station = s.station;
    } else {
      s.dc_delay = prev_delay + (prev_rt - rt) / 2;
      // At one instant, this slave's local time is (its latch - its delay) - (ref's latch) ahead.
      s.dc_offset = ref_offset + static_cast<std::int64_t>(ref_local - times[i].local) + s.dc_delay;
    }
    prev_rt = rt;
    prev_delay = s.dc_delay;
    ++result.dc_slaves;
    require(t.fpwr(s.station, reg::kDcSystemTimeOffset, bytes64(static_cast<std::uint64_t>(s.dc_offset))), 1,
            "FPWR DC system time offset", i);
    require(t.fpwr_value<std::uint32_t>(s.station, reg::kDcSystemTimeDelay, static_cast<std::uint32_t>(s.dc_delay)), 1,
            "FPWR DC system time delay", i);
  }
  if (result.dc_slaves == 0) return result;

  // 4. Static drift compensation: the reference's system time to every other slave, many times.
  std::array<std::uint8_t, 8> time{};
  for (int n = 0; n < options.drift_frames; ++n) t.frmw(result.reference_station, reg::kDcSystemTime, time);
  return result;
}

std::uint64_t activate_sync0(Master& master, std::uint32_t cycle, std::int32_t shift, Nanos lead) {
  Transport& t = master.transport();
  auto& slaves = master.slaves();
  std::uint64_t start = 0;
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    Slave& s = slaves[i];
    if (!s.dc_supported) continue;
    require(t.fpwr_value<std::uint8_t>(s.station, reg::kDcSyncActivation, 0), 1, "FPWR 0x0981 (SYNC off)", i);
    require(t.fpwr_value<std::uint8_t>(s.station, reg::kDcCyclicUnitControl, 0), 1, "FPWR 0x0980 (ECAT owns sync)", i);
    if (start == 0) {
      std::array<std::uint8_t, 8> now{};
      require(t.fprd(s.station, reg::kDcSystemTime, now), 1, "FPRD DC system time", i);
      const std::uint64_t at = le64(now) + static_cast<std::uint64_t>(lead);
      // One start time for the whole line: the slaves share the system time.
      start = (cycle ? (at / cycle + 1) * cycle : at) + static_cast<std::uint64_t>(static_cast<std::int64_t>(shift));
    }
    require(t.fpwr(s.station, reg::kDcStartTime, bytes64(start)), 1, "FPWR DC start time", i);
    require(t.fpwr_value<std::uint32_t>(s.station, reg::kDcSync0Cycle, cycle), 1, "FPWR SYNC0 cycle", i);
    require(t.fpwr_value<std::uint8_t>(s.station, reg::kDcSyncActivation,
                                       reg::kDcSyncActivateCyclic | reg::kDcSyncActivateSync0),
            1, "FPWR 0x0981 (SYNC0 on)", i);
  }
  return start;
}

}  // namespace vdrive::master
