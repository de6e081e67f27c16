#include "vdrive/drive/modes/homing_rules.hpp"

#include <array>

namespace vdrive::drive {

namespace {

// DS5C1: -1 pushes forward (正向碰撞回原), -2 backward (反向), at 6099h-02h (L3278-L3281, L3551, L3568).
constexpr std::array<HardStopMethod, 2> kDs5c1 = {{
    {-1, +1, true, false},
    {-2, -1, true, false},
}};

// DS1000A-EC: -1 negative / -2 positive, then the index in the reverse direction (L2957-L2961);
// -3 negative / -4 positive, home where the torque was detected (L2965-L2967). The push runs at the
// "search for switch" speed: a hard stop is the sensor here (6099h-01h, L2978).
constexpr std::array<HardStopMethod, 4> kDs1000a = {{
    {-1, -1, false, true},
    {-2, +1, false, true},
    {-3, -1, false, false},
    {-4, +1, false, false},
}};

template <std::size_t N>
const HardStopMethod* find(const std::array<HardStopMethod, N>& rows, std::int8_t method) {
  for (const HardStopMethod& r : rows)
    if (r.method == method) return &r;
  return nullptr;
}

}  // namespace

const HardStopMethod* HomingRules::hard_stop(std::int8_t method) const {
  switch (vendor) {
    case Vendor::Ds5c1HardStop: return find(kDs5c1, method);
    case Vendor::Ds1000aTorqueLimit: return find(kDs1000a, method);
    default: return nullptr;
  }
}

HomingRules homing_rules_for(const profile::ProductProfile& profile) {
  HomingRules r;
  if (profile.id == "a6b") {
    r.vendor = HomingRules::Vendor::ManufacturerOnly;
    if (profile.find_alarm("27.7") != nullptr) r.cancel_after_detection_alarm = "27.7";
  } else if (profile.id == "ds5c1") {
    r.vendor = HomingRules::Vendor::Ds5c1HardStop;
    r.offset_only_for_current_position = true;
  } else if (profile.id == "ds1000a") {
    r.vendor = HomingRules::Vendor::Ds1000aTorqueLimit;
    r.abrupt_sensor_stop = true;
    // No 6099h = 0 exemption is documented; 33/34 "move to home" at 6099h-02h (L2980).
    r.index_methods_use_switch_speed = false;
  }
  return r;
}

}  // namespace vdrive::drive
