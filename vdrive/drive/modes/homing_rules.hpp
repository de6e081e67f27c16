#pragma once
// The vendor homing methods that push against a hard stop (6098h < 0), as a product's homing
// section lists them (profile.homing.vendor_methods and hard_stops). The homing mode reads the rest
// of its product rules (reference value, sensor stops, index speed, cancel alarm) from that section
// directly.
#include <cstdint>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

using HardStopMethod = profile::HardStopMethod;

// The hard-stop row of `method`; nullptr when it is not one.
const HardStopMethod* find_hard_stop(const profile::HomingSpec& homing, std::int8_t method);

}  // namespace vdrive::drive
