#pragma once
// One ESC watchdog (process data or PDI). Its period is (divider + 2) * 40 ns * time, from the
// watchdog divider (0x0400) and the watchdog time register (0x0410 / 0x0420); time 0 disables
// it. It is (re)started by trigger() — completed SyncManager writes with watchdog trigger
// enabled, or PDI accesses — and expires if not triggered again within one period.
// Time-driven through expired()/deadline(); no threads.
#include <cstdint>

#include "common/clock.hpp"

namespace vdrive::esc {

class Watchdog {
public:
  void configure(std::uint16_t divider, std::uint16_t time);
  void reset();

  void trigger(Nanos now);
  // True exactly once when the running watchdog's period has passed at `now`; it then stops
  // until the next trigger.
  bool expire_if_due(Nanos now);
  // Stops without expiring (the caller reports the expiry itself, e.g. an injected fault).
  void stop() { running_ = false; }
  // Expiry time of the running watchdog, or INT64_MAX.
  Nanos deadline() const;

  bool running() const { return running_; }
  Nanos period() const { return period_; }

private:
  Nanos period_ = 0;
  Nanos last_trigger_ = 0;
  bool running_ = false;
};

}  // namespace vdrive::esc
