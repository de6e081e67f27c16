#pragma once
// User units <-> motor units (CiA 402 factor group): encoder resolution 608Fh, gear ratio 6091h,
// feed constant 6092h and polarity 607Eh. The drive latches them only at the moments its manual
// names (power-on, Init->PreOp, homing done ...): apply() is called then, never per step.
//   motor revolutions per user unit = (6091h-01h / 6091h-02h) / (6092h-01h / 6092h-02h)
//   increments per user unit        = (608Fh-01h / 608Fh-02h) * motor revolutions per user unit
#include <cstdint>

namespace vdrive::drive {

struct FactorGroup {
  std::uint32_t encoder_increments = 1, encoder_revolutions = 1;   // 608Fh-01h/-02h
  std::uint32_t gear_motor_revolutions = 1, gear_shaft_revolutions = 1;  // 6091h-01h/-02h
  std::uint32_t feed = 1, feed_shaft_revolutions = 1;              // 6092h-01h/-02h
  std::uint8_t polarity = 0;                                       // 607Eh
};

// The factor group's objects as they hold (0 for a subindex that is 0 or absent).
struct FactorObjects {
  std::uint32_t encoder_increments = 0, encoder_revolutions = 0;  // 608Fh-01h/-02h
  std::uint32_t gear_motor = 0, gear_shaft = 0;                   // 6091h-01h/-02h
  bool has_feed = false;                                          // 6092h exists
  std::uint32_t feed = 0, feed_shaft = 0;                         // 6092h-01h/-02h
  std::uint8_t polarity = 0;                                      // 607Eh
};

// What the drive makes of them: 608Fh-01h = 0 (the DS1000A-EC's factory value) is the motor's own
// encoder resolution `counts_per_rev`; no 6092h is a feed of one encoder revolution; any other 0
// counts as 1. The drive (DriveEngine) and the tools that scale its values (vdrive plot) both use it.
FactorGroup factor_group(const FactorObjects& objects, std::uint32_t counts_per_rev);

class UnitScaling {
public:
  // Polarity bits: 7 position, 6 velocity, 5 torque (A6B/DS5C1); the DS1000-EC has no bit 5 and
  // its torque follows the velocity bit (torque_follows_velocity).
  void apply(const FactorGroup& f, bool torque_follows_velocity = false);

  const FactorGroup& factors() const { return f_; }
  double increments_per_user() const { return inc_per_user_; }
  double motor_rad_per_user() const { return rad_per_user_; }
  double increments_per_motor_rev() const { return inc_per_rev_; }

  // Motor shaft (rad, rad/s) <-> user units, with polarity. Positions are relative: the caller
  // adds its reference (home) offset.
  double position_to_user(double motor_rad) const { return pos_sign_ * motor_rad / rad_per_user_; }
  double position_to_motor(double user) const { return pos_sign_ * user * rad_per_user_; }
  double velocity_to_user(double motor_rad_s) const { return vel_sign_ * motor_rad_s / rad_per_user_; }
  double velocity_to_motor(double user_s) const { return vel_sign_ * user_s * rad_per_user_; }
  double torque_sign() const { return torque_sign_; }
  double position_sign() const { return pos_sign_; }

  // Motor speed in r/min (6080h, stop thresholds) as user units/s, and back.
  double rpm_to_user(double rpm) const;
  double user_to_rpm(double user_s) const;

private:
  FactorGroup f_;
  double inc_per_rev_ = 1.0, inc_per_user_ = 1.0, rad_per_user_ = 1.0;
  double pos_sign_ = 1.0, vel_sign_ = 1.0, torque_sign_ = 1.0;
};

}  // namespace vdrive::drive
