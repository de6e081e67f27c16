#include "vdrive/drive/alarms/xinje_alarm_history.hpp"

#include "vdrive/drive/alarms/alarm_code.hpp"

namespace vdrive::drive {

namespace {
constexpr std::uint16_t kU1 = 0x3100;   // U1-00 (L7380)
}  // namespace

XinjeAlarmHistory::XinjeAlarmHistory(od::ObjectStore& store)
    : current_alarm_(store, kU1), current_warning_(store, kU1 + 1), run_count_(store, kU1 + 12),
      total_count_(store, kU1 + 14) {
  for (std::size_t i = 0; i < recent_.size(); ++i)
    recent_[i] = ObjectRef<std::uint16_t>(store, static_cast<std::uint16_t>(kU1 + 16 + i));
}

void XinjeAlarmHistory::record(const profile::AlarmSpec& alarm) {
  log_.record(alarm);
  ++since_power_on_;
  publish();
}

void XinjeAlarmHistory::power_on() {
  since_power_on_ = 0;   // U1-12 counts from this power-on (L9084)
  publish();
}

void XinjeAlarmHistory::current(const profile::AlarmSpec* alarm, const profile::AlarmSpec* warning) {
  current_alarm_.set(alarm ? parse_alarm_code(alarm->code).display : 0);
  current_warning_.set(warning ? parse_alarm_code(warning->code).display : 0);
}

void XinjeAlarmHistory::publish() {
  run_count_.set(static_cast<std::uint16_t>(since_power_on_));
  total_count_.set(static_cast<std::uint16_t>(log_.total()));
  for (std::size_t i = 0; i < recent_.size(); ++i) {
    const profile::AlarmSpec* a = log_.newest(i + 1);   // U1-16 = 2nd latest
    recent_[i].set(a ? parse_alarm_code(a->code).display : 0);
  }
}

}  // namespace vdrive::drive
