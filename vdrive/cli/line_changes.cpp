#include "vdrive/cli/line_changes.hpp"

#include <fmt/core.h>

#include <algorithm>

#include "ethercat/registers.hpp"
#include "ethercat/slave_ref.hpp"
#include "master/al_state.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::cli {
namespace {

// The alarm the drive says it raised; by 603Fh only when it does not say, since one 603Fh can be
// several alarms (A6B FF51h is Err81.0, 81.1, 81.4, 81.5 and 81.6, L32610-L32618).
std::string alarm_text(const profile::ProductProfile& p, std::uint16_t error_code, int index) {
  const profile::AlarmSpec* a = index >= 0 && static_cast<std::size_t>(index) < p.alarms.size()
                                    ? &p.alarms[static_cast<std::size_t>(index)]
                                    : p.alarm_with_error_code(error_code);
  if (a != nullptr) {
    const std::string& name = a->name_en.empty() ? a->name : a->name_en;
    return fmt::format("alarm {} {} (603Fh {:04X}h)", a->code, name, error_code);
  }
  return fmt::format("alarm 603Fh {:04X}h", error_code);
}

}  // namespace

std::vector<std::string> line_changes(const runtime::StatusSample& before, const runtime::StatusSample& now,
                                      const network::Network& network, std::size_t slaves_before) {
  std::vector<std::string> lines;
  const std::size_t n = std::min({before.slaves.size(), now.slaves.size(), network.size()});
  // A fault that follows a host stall says so: the user can tell the host from their master.
  const std::string stall = runtime::after_stall(now.recent_stall);
  for (std::size_t i = 0; i < n; ++i) {
    const runtime::SlaveStatus& b = before.slaves[i];
    const runtime::SlaveStatus& a = now.slaves[i];
    const profile::ProductProfile& p = network.profile(i);
    const std::string who = ecat::slave_label(slaves_before + i, a.station, p.id);
    const bool was_error = (b.al_status & ecat::reg::kAlErrorFlag) != 0, is_error = (a.al_status & ecat::reg::kAlErrorFlag) != 0;
    if ((a.al_status & 0x0F) != (b.al_status & 0x0F))
      lines.push_back(fmt::format("{}: {} -> {}", who, runtime::al_state_name(b.al_status), runtime::al_state_name(a.al_status)));
    if (is_error && (!was_error || a.al_status_code != b.al_status_code))
      lines.push_back(fmt::format("{}: AL error 0x{:04X} {}, in {}{}", who, a.al_status_code,
                                  master::al_status_code_text(a.al_status_code), runtime::al_state_name(a.al_status), stall));
    else if (was_error && !is_error)
      lines.push_back(fmt::format("{}: AL error acknowledged", who));
    if (a.error_code != b.error_code || (a.error_code != 0 && a.alarm != b.alarm))
      lines.push_back(a.error_code != 0 ? fmt::format("{}: {}{}", who, alarm_text(p, a.error_code, a.alarm), stall)
                                        : fmt::format("{}: alarm cleared", who));
  }
  if (before.onward && now.onward && before.onward->link != now.onward->link)
    lines.push_back(now.onward->link ? "onward link up: the line goes on beyond the last slave here"
                                     : "onward link down: the line ends at the last slave here");
  return lines;
}

std::vector<std::string> host_stall_lines(const runtime::HostStalls& stalls, std::uint64_t& seen, std::size_t slaves_before) {
  std::vector<std::string> lines;
  const std::uint64_t count = stalls.count();
  for (std::uint64_t k = seen + 1; k <= count; ++k) {
    if (const std::optional<runtime::HostStall> s = stalls.get(k)) lines.push_back(runtime::describe(*s, slaves_before));
    else if (k + runtime::HostStalls::kLog <= count) {  // overwritten: say how many in one go
      const std::uint64_t skipped = count - runtime::HostStalls::kLog + 1 - k;
      lines.push_back(fmt::format("{} more host stall{} (longest so far {})", skipped, skipped == 1 ? "" : "s",
                                  runtime::stall_ms(stalls.longest())));
      k += skipped - 1;
    }
  }
  seen = count;
  return lines;
}

}  // namespace vdrive::cli
