#include "vdrive/runtime/line_status.hpp"

#include <fmt/format.h>

#include <limits>
#include <map>

#include "ethercat/registers.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::runtime {
namespace {

constexpr std::uint16_t kAlStatus = ecat::reg::kAlStatus, kAlStatusCode = ecat::reg::kAlStatusCode;
constexpr std::uint16_t kErrorCountersFirst = ecat::reg::kRxErrorCounter,
                        kErrorCountersLast = ecat::reg::kErrorCountersLast;
constexpr std::uint16_t kAlErrorFlag = ecat::reg::kAlErrorFlag;
constexpr std::size_t kSlavesShownOneByOne = 8;
constexpr std::uint16_t kErrorCode = 0x603F;

std::string slave_text(const SlaveStatus& s) {
  std::string text = al_state_name(s.al_status);
  if (s.al_status & kAlErrorFlag) text += fmt::format("+E({:04X})", s.al_status_code);
  return text;
}

}  // namespace

SlaveStatus slave_status(network::Network& network, std::size_t i) {
  esc::Esc& esc = network.esc(i);
  SlaveStatus s;
  s.al_status = esc.peek_u16(kAlStatus);
  s.al_status_code = esc.peek_u16(kAlStatusCode);
  s.station = esc.peek_u16(ecat::reg::kStationAddress);
  for (std::uint16_t a = kErrorCountersFirst; a <= kErrorCountersLast; ++a) s.rx_errors += esc.peek(a);
  if (drive::DriveEngine* engine = network.firmware(i).drive(); engine != nullptr) {
    s.alarm = static_cast<std::int16_t>(engine->alarms().newest_index());
    od::ObjectStore& objects = network.firmware(i).objects();
    if (const od::EntryDesc* e = objects.dictionary().find(kErrorCode, 0); e != nullptr && e->value_bytes >= 2) {
      const std::span<const std::uint8_t> raw = objects.raw(*e);
      s.error_code = static_cast<std::uint16_t>(raw[0] | raw[1] << 8);
    }
  }
  return s;
}

void LineStatusPublisher::sample() {
  for (std::size_t i = 0; i < status_.slaves(); ++i) {
    const SlaveStatus s = slave_status(network_, i);
    status_.publish(i, s);
  }
  if (wire_source_) status_.publish_wire(wire_source_());
}

void LineStatusPublisher::poll(Nanos now) {
  if (now >= due_) {
    sample();
    status_.publish_time(now);
    due_ = now + period_;
  }
  if (next_ != nullptr) next_->poll(now);
}

Nanos LineStatusPublisher::next_deadline() const {
  const Nanos next = next_ != nullptr ? next_->next_deadline() : std::numeric_limits<Nanos>::max();
  return next < due_ ? next : due_;
}

StatusSample take_sample(const LineStatus& status, const LoopCounters& counters, Nanos now) {
  StatusSample s;
  s.time = now;
  for (std::size_t i = 0; i < status.slaves(); ++i) s.slaves.push_back(status.slave(i));
  s.frames_in = counters.frames_in.load(std::memory_order_relaxed);
  s.frames_out = counters.frames_out.load(std::memory_order_relaxed);
  s.dropped = counters.dropped.load(std::memory_order_relaxed);
  s.send_failed = counters.send_failed.load(std::memory_order_relaxed);
  if (counters.has_onward.load(std::memory_order_relaxed))
    s.onward = StatusSample::Onward{counters.onward_link.load(std::memory_order_relaxed),
                                    counters.onward.load(std::memory_order_relaxed),
                                    counters.returned.load(std::memory_order_relaxed)};
  s.wire = status.wire();
  s.host_stalls = counters.stalls.count();
  s.longest_stall = counters.stalls.longest();
  s.recent_stall = counters.stalls.just_before(status.sampled_at());
  return s;
}

std::string al_state_name(std::uint16_t al_status) {
  switch (al_status & 0x0F) {
    case 0: return "?";  // not read: a later part of a line over processes that did not answer
    case 1: return "Init";
    case 2: return "PreOp";
    case 3: return "Boot";
    case 4: return "SafeOp";
    case 8: return "Op";
    default: return fmt::format("0x{:X}", al_status & 0x0F);
  }
}

std::string format_status_line(const StatusSample& now, const StatusSample* before) {
  std::string line = fmt::format("{} slave{}", now.slaves.size(), now.slaves.size() == 1 ? "" : "s");
  std::uint64_t rx_errors = 0;
  for (const SlaveStatus& s : now.slaves) rx_errors += s.rx_errors;
  if (now.slaves.size() <= kSlavesShownOneByOne) {
    for (std::size_t i = 0; i < now.slaves.size(); ++i) line += fmt::format(" {}:{}", i + 1, slave_text(now.slaves[i]));
  } else {
    std::map<std::string, std::size_t> counts;
    std::size_t first_error = 0;
    for (std::size_t i = 0; i < now.slaves.size(); ++i) {
      const SlaveStatus& s = now.slaves[i];
      ++counts[al_state_name(s.al_status) + (s.al_status & kAlErrorFlag ? "+E" : "")];
      if ((s.al_status & kAlErrorFlag) && first_error == 0) first_error = i + 1;
    }
    const char* sep = " ";
    for (const auto& [state, n] : counts) {
      line += fmt::format("{}{} {}", sep, state, n);
      sep = ", ";
    }
    if (first_error != 0)
      line += fmt::format(" (first error: {} {:04X})", first_error, now.slaves[first_error - 1].al_status_code);
  }
  line += fmt::format(" | frames {} in {} out", now.frames_in, now.frames_out);
  if (before != nullptr && now.time > before->time && now.frames_in >= before->frames_in) {
    const double seconds = static_cast<double>(now.time - before->time) / 1e9;
    line += fmt::format(", {:.0f}/s", static_cast<double>(now.frames_in - before->frames_in) / seconds);
  }
  line += fmt::format(" | rx errors {} | dropped {} | send failed {}", rx_errors, now.dropped, now.send_failed);
  if (now.wire) line += fmt::format(" | wire fault dropped {} corrupted {}", now.wire->dropped, now.wire->corrupted);
  if (now.onward)
    line += fmt::format(" | onward {}, {} on, {} back", now.onward->link ? "up" : "down", now.onward->sent, now.onward->returned);
  if (now.host_stalls > 0) line += fmt::format(" | host stalls {}, longest {}", now.host_stalls, stall_ms(now.longest_stall));
  return line;
}

}  // namespace vdrive::runtime
