#include "vdrive/drive/modes/homing_rules.hpp"

namespace vdrive::drive {

const HardStopMethod* HomingRules::hard_stop(std::int8_t method) const {
  for (const HardStopMethod& r : hard_stops)
    if (r.method == method) return &r;
  return nullptr;
}

HomingRules homing_rules_for(const profile::ProductProfile& profile) {
  const profile::HomingSpec& h = profile.homing;
  HomingRules r;
  r.vendor = h.vendor_methods;
  r.hard_stops = h.hard_stops;
  r.offset_only_for_current_position = h.offset_only_for_current_position;
  r.abrupt_sensor_stop = h.abrupt_sensor_stop;
  r.index_methods_use_switch_speed = h.index_methods_use_switch_speed;
  r.cancel_after_detection_alarm = h.cancel_after_detection_alarm;
  return r;
}

}  // namespace vdrive::drive
