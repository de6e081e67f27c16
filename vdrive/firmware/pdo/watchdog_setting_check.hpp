#pragma once
// The process-data watchdog setting check at PreOp->SafeOp (A6B Err81.4 L33447-L33481, DS5C1
// E-814 L7126): when the SM2 watchdog is enabled (SM2 control bit 6 and a non-zero 0420h) its
// time must be at least min_cycles x the cycle time in SM2/DC mode, or min_free_run_ns in free
// run. The time is the ESC's: (0400h + 2) x 40 ns x 0420h.
#include <cstdint>

#include "common/clock.hpp"
#include "ethercat/registers.hpp"
#include "vdrive/firmware/pdo/pdo_limits.hpp"

namespace vdrive::firmware::pdo {

inline Nanos process_data_watchdog_time(std::uint16_t divider, std::uint16_t time) {
  return (static_cast<Nanos>(divider) + 2) * ecat::reg::kWatchdogClockNs * static_cast<Nanos>(time);
}

struct WatchdogSetting {
  bool enabled = false;        // SM2 control bit 6 set and 0420h != 0
  Nanos time = 0;              // process_data_watchdog_time()
  bool synchronised = false;   // SM2 or DC mode (1C32h-01h != 0 or DC active)
  std::uint32_t cycle_ns = 0;  // 1C32h-02h
};

inline bool watchdog_setting_ok(const WatchdogSetting& s, const WatchdogLimits& limits) {
  if (!s.enabled) return true;
  const Nanos minimum = s.synchronised
                            ? static_cast<Nanos>(limits.min_cycles) * static_cast<Nanos>(s.cycle_ns)
                            : static_cast<Nanos>(limits.min_free_run_ns);
  return s.time >= minimum;
}

}  // namespace vdrive::firmware::pdo
