#include "esc_model/watchdog.hpp"

#include <cstdint>

#include "ethercat/registers.hpp"

namespace vdrive::esc {

void Watchdog::configure(std::uint16_t divider, std::uint16_t time) {
  period_ = (static_cast<Nanos>(divider) + 2) * ecat::reg::kWatchdogClockNs * static_cast<Nanos>(time);
  if (period_ == 0) running_ = false;
}

void Watchdog::reset() {
  period_ = 0;
  last_trigger_ = 0;
  running_ = false;
}

void Watchdog::trigger(Nanos now) {
  last_trigger_ = now;
  running_ = period_ > 0;
}

bool Watchdog::expire_if_due(Nanos now) {
  if (!running_ || now < last_trigger_ + period_) return false;
  running_ = false;
  return true;
}

Nanos Watchdog::deadline() const { return running_ ? last_trigger_ + period_ : INT64_MAX; }

}  // namespace vdrive::esc
