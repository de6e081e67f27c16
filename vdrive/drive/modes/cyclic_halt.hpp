#pragma once
// Halt (6040h bit 8) in the cyclic and interpolated modes: the axis stops with the ramp 605Dh
// selects and stays in Operation enabled (A6B L27410-L27442, DS5C1 L4379-L4509, DS1000A-EC 605Dh
// default 1 L4899-L4907):
//   1  profile deceleration 6084h    2  quick-stop deceleration 6085h    3  60C6h max deceleration
//      (torque modes: 1 and 2 ramp the torque down at 6087h, 3 drops it to zero at once).
// An out-of-range 605Dh runs as 1; a deceleration of 0 counts as 1 (A6B L12952-L13016).
#include <cstdint>

#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class CyclicHalt {
public:
  explicit CyclicHalt(od::ObjectStore& o)
      : option_(o, 0x605D, 0, 1), profile_dec_(o, 0x6084), quick_stop_dec_(o, 0x6085), max_dec_(o, 0x60C6),
        torque_slope_(o, 0x6087) {}

  // User units/s^2.
  double deceleration() const {
    std::uint32_t dec = 0;
    switch (option_.get()) {
      case 2: dec = quick_stop_dec_.get(); break;
      case 3: dec = max_dec_.get(); break;
      default: dec = profile_dec_.get(); break;
    }
    return dec == 0 ? 1.0 : static_cast<double>(dec);
  }
  // Torque modes: 0.1 % per second; 0 when the torque drops at once (605Dh = 3).
  double torque_slope() const {
    if (option_.get() == 3) return 0.0;
    const std::uint32_t slope = torque_slope_.get();
    return slope == 0 ? 1.0 : static_cast<double>(slope);
  }

private:
  ObjectRef<std::int16_t> option_;
  ObjectRef<std::uint32_t> profile_dec_, quick_stop_dec_, max_dec_, torque_slope_;
};

}  // namespace vdrive::drive
