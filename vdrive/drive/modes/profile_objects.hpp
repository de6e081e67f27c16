#pragma once
// The profile parameters pp and pv share, resolved once: accelerations 6083h/6084h capped by
// 60C5h/60C6h, the speed limit min(607Fh, 6080h) and the halt ramp chosen by 605Dh. A value of 0
// in 6083h/6084h/60C5h/60C6h/6085h counts as 1 (A6B L12952-L13016), so no ramp ever divides by 0
// or stalls. Objects a product lacks (60C6h on some) read as "no cap".
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class ProfileObjects {
public:
  explicit ProfileObjects(const DriveContext& ctx)
      : units_(ctx.units), profile_acc_(ctx.objects, 0x6083), profile_dec_(ctx.objects, 0x6084),
        max_acc_(ctx.objects, 0x60C5, 0, kNoCap), max_dec_(ctx.objects, 0x60C6, 0, kNoCap),
        quick_stop_dec_(ctx.objects, 0x6085), max_profile_velocity_(ctx.objects, 0x607F, 0, kNoCap),
        max_motor_speed_(ctx.objects, 0x6080, 0, kNoCap), halt_option_(ctx.objects, 0x605D, 0, 1) {}

  // user units/s^2
  double acceleration() const { return std::min(at_least_one(profile_acc_.get()), at_least_one(max_acc_.get())); }
  double deceleration() const { return std::min(at_least_one(profile_dec_.get()), at_least_one(max_dec_.get())); }
  double quick_stop_deceleration() const { return at_least_one(quick_stop_dec_.get()); }

  // min(607Fh, 6080h) in user units/s (6080h is r/min); 0 when either is 0 (no motion).
  double velocity_limit() const {
    const double motor = units_.rpm_to_user(static_cast<double>(max_motor_speed_.get()));
    return std::min(static_cast<double>(max_profile_velocity_.get()), std::abs(motor));
  }

  // Deceleration of a halt (6040h bit 8) in pp/pv by 605Dh: 1 profile deceleration 6084h,
  // 2 quick-stop deceleration 6085h, 3 current limit = the steepest ramp 60C6h (A6B L27410-L27442,
  // DS5C1 L4481). Values outside 1..3 (refused by the dictionary's range) act as 1.
  double halt_deceleration() const {
    switch (halt_option_.get()) {
      case 2: return quick_stop_deceleration();
      case 3: return max_dec_.present() ? at_least_one(max_dec_.get()) : quick_stop_deceleration();
      default: return deceleration();
    }
  }

private:
  static constexpr std::uint32_t kNoCap = std::numeric_limits<std::uint32_t>::max();
  static double at_least_one(std::uint32_t v) { return v == 0 ? 1.0 : static_cast<double>(v); }

  const UnitScaling& units_;
  ObjectRef<std::uint32_t> profile_acc_, profile_dec_, max_acc_, max_dec_, quick_stop_dec_;
  ObjectRef<std::uint32_t> max_profile_velocity_, max_motor_speed_;
  ObjectRef<std::int16_t> halt_option_;
};

}  // namespace vdrive::drive
