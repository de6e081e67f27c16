#pragma once
// How one product runs homing beyond the standard method table: its vendor methods (6098h < 0),
// which value the reference point takes, how it stops at a sensor, and which alarm a cancelled
// homing raises. Chosen by profile id at construction (the profile data has no homing behaviour
// fields yet); everything else comes from profile.homing and profile.drive.
#include <cstdint>
#include <string_view>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

// A vendor "push against a hard stop" method.
struct HardStopMethod {
  std::int8_t method = 0;
  int direction = +1;          // push direction
  bool push_at_zero_speed = false;  // push at 6099h-02h (DS5C1 L3551) instead of 6099h-01h
  bool index_after = false;    // then the index pulse(s) in the opposite direction (DS1000A-EC -1/-2)
};

struct HomingRules {
  enum class Vendor : std::uint8_t {
    None,
    ManufacturerOnly,    // A6B -1..-4: "manufacturer use" (L17864-L17870), no sequence documented
    Ds5c1HardStop,       // DS5C1 -1/-2: P9-16..P9-20, P7-20 (L3549-L3568)
    Ds1000aTorqueLimit,  // DS1000A-EC -1..-4: torque limit (+ index) (L2957-L2967)
  } vendor = Vendor::None;
  // 607Ch applies only to 35/37; every other method makes the reference point 0 (DS5C1 L3504, L3376).
  bool offset_only_for_current_position = false;
  // Every sensor stop is abrupt, 609Ah only accelerates (DS1000A-EC L2986-L2988); otherwise
  // reversals decelerate with 609Ah and the final stop is a servo lock (A6B L17978-L17980).
  bool abrupt_sensor_stop = false;
  // Methods 33/34 run on 6099h-01h alone (its 6099h-02h = 0 is no error: A6B L18663-L18665,
  // DS5C1 L3526).
  bool index_methods_use_switch_speed = true;
  // Alarm raised when homing is cancelled between home detection and completion (A6B Err27.7,
  // L18526-L18528); empty = none.
  std::string_view cancel_after_detection_alarm;

  // The hard-stop rows (DS5C1 and DS1000A-EC); nullptr when `method` is not one of them.
  const HardStopMethod* hard_stop(std::int8_t method) const;
};

HomingRules homing_rules_for(const profile::ProductProfile& profile);

}  // namespace vdrive::drive
