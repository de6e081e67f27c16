#pragma once
// How one product runs homing beyond the standard method table: its vendor methods (6098h < 0),
// which value the reference point takes, how it stops at a sensor, and which alarm a cancelled
// homing raises. Taken from the product's homing section once, at construction; the hard-stop
// rows stay in the profile, which outlives the drive.
#include <cstdint>
#include <span>
#include <string_view>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

using HardStopMethod = profile::HardStopMethod;

struct HomingRules {
  using Vendor = profile::HomingVendorMethods;
  Vendor vendor = Vendor::None;
  std::span<const HardStopMethod> hard_stops;
  // See profile::HomingSpec for the meaning of each flag.
  bool offset_only_for_current_position = false;
  bool abrupt_sensor_stop = false;
  bool index_methods_use_switch_speed = true;
  std::string_view cancel_after_detection_alarm;  // empty = none

  // The hard-stop row of `method`; nullptr when it is not one.
  const HardStopMethod* hard_stop(std::int8_t method) const;
};

HomingRules homing_rules_for(const profile::ProductProfile& profile);

}  // namespace vdrive::drive
