#include "master/drive_recovery.hpp"

#include <algorithm>

namespace vdrive::master {

DriveRecovery::Event DriveRecovery::update(Nanos now, bool enabled, std::uint16_t error_code) {
  Event event = Event::none;
  if (!out()) {
    if (was_enabled_ && !enabled) {
      out_since_ = now;
      out_overdue_ = false;
      code_ = error_code;
      ++outages_;
      event = Event::lost;
    }
  } else if (enabled) {
    last_duration_ = now - out_since_;
    longest_ = std::max(longest_, last_duration_);
    if (!out_overdue_) count(code_);  // an overdue outage was counted when it became overdue
    out_since_ = -1;
    ++recoveries_;
    event = Event::recovered;
  } else {
    // The error code often shows a cycle or two after the status word drops Operation enabled.
    if (code_ == 0 && error_code != 0) code_ = error_code;
    if (!out_overdue_ && now - out_since_ > bound_) {
      out_overdue_ = true;
      ++overdue_;
      count(code_);
      longest_ = std::max(longest_, now - out_since_);
      event = Event::overdue;
    }
  }
  was_enabled_ = enabled;
  return event;
}

void DriveRecovery::count(std::uint16_t code) {
  for (std::size_t i = 0; i < used_; ++i) {
    if (codes_[i].code == code) {
      ++codes_[i].count;
      return;
    }
  }
  if (used_ == codes_.size()) {
    ++other_codes_;
    return;
  }
  codes_[used_++] = AlarmCount{code, 1};
}

}  // namespace vdrive::master
