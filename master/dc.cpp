#include "master/dc.hpp"

#include <fmt/format.h>

#include <array>
#include <vector>

#include "master/dc_topology.hpp"
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
  if (!wkc || *wkc != expected) throw MasterError(fmt::format("slave {}: {} not taken", slave + 1, what));
}
}  // namespace

DcTopology measure_dc_topology(Master& master, std::vector<std::uint64_t>* local_times) {
  Transport& t = master.transport();
  auto& slaves = master.slaves();
  // Latch the receive times of one frame at every port of every slave.
  std::array<std::uint8_t, 4> latch{};
  if (!t.bwr(reg::kDcReceiveTimes, latch)) throw MasterError("BWR 0x0900 (DC receive time latch): no reply");
  // Every slave's port times and DL status (a slave without DC shows zeros and keeps its place).
  std::vector<PortTimes> seen(slaves.size());
  if (local_times) local_times->assign(slaves.size(), 0);
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    Slave& s = slaves[i];
    seen[i].dl_status = t.fprd_value<std::uint16_t>(s.station, reg::kDlStatus).value_or(0);
    if (!s.dc_supported) continue;
    std::array<std::uint8_t, 16> ports{};
    std::array<std::uint8_t, 8> unit{};
    require(t.fprd(s.station, reg::kDcReceiveTimes, ports), 1, "FPRD DC receive times", i);
    require(t.fprd(s.station, reg::kDcReceiveTimeUnit, unit), 1, "FPRD DC receive time unit", i);
    for (std::size_t p = 0; p < 4; ++p) seen[i].rx[p] = le32(std::span(ports).subspan(4 * p, 4));
    if (local_times) (*local_times)[i] = le64(unit);  // 0x0918: local time of the port-0 receive
  }
  DcTopology topology = compute_dc_topology(seen);
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    slaves[i].parent = static_cast<std::uint16_t>(topology.parent[i]);
    slaves[i].parent_port = topology.parent_port[i];
  }
  return topology;
}

DcResult configure_dc(Master& master, const DcOptions& options) {
  Transport& t = master.transport();
  DcResult result;
  auto& slaves = master.slaves();
  // 1. Receive times at every port, and what they say about the line or tree.
  std::vector<std::uint64_t> local;
  const DcTopology topology = measure_dc_topology(master, &local);

  // 2./3. Delays from the topology, offsets to the reference's time base.
  std::size_t ref = slaves.size();
  std::uint64_t ref_local = 0;
  std::int64_t ref_offset = 0;
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    Slave& s = slaves[i];
    if (!s.dc_supported) continue;
    if (ref == slaves.size()) {
      ref = i;
      ref_local = local[i];
      // The reference clock starts at the master's time.
      ref_offset = static_cast<std::int64_t>(static_cast<std::uint64_t>(master.clock().now()) - ref_local);
      s.dc_delay = 0;
      s.dc_offset = ref_offset;
      result.reference_station = s.station;
    } else {
      s.dc_delay = topology.delay[i] - topology.delay[ref];
      // At one instant, this slave's local time is (its latch - its delay) - (ref's latch) ahead.
      s.dc_offset = ref_offset + static_cast<std::int64_t>(ref_local - local[i]) + s.dc_delay;
    }
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
