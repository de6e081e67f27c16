#include "vdrive/drive/modes/homing_rules.hpp"

namespace vdrive::drive {

const HardStopMethod* find_hard_stop(const profile::HomingSpec& homing, std::int8_t method) {
  for (const HardStopMethod& r : homing.hard_stops)
    if (r.method == method) return &r;
  return nullptr;
}

}  // namespace vdrive::drive
