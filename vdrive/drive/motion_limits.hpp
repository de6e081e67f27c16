#pragma once
// The limits every set-point passes before the control loops (issue 5 item 3): software position
// limits 607Dh (profile.drive.soft_limits: always once referenced / only after homing / ignored),
// limit switches (profile.drive.limit_switches: no motion into an active limit), and the torque
// limit in force: min(6072h, 60E0h/60E1h, the product's clamp, the set-point's own limit). Reports
// statusword bit 11 "internal limit active" when any of them acted.
#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/drive_types.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class MotionLimits {
public:
  explicit MotionLimits(const DriveContext& ctx);

  // `homing`: homing runs (it moves onto the switches on purpose; soft limits do not apply).
  // `homed`: a homing run completed since power-on.
  Setpoint apply(const Setpoint& sp, const AxisSample& s, bool homing, bool homed);

  bool internal_limit() const { return internal_limit_; }
  bool limit_switch_active() const { return switch_active_; }   // a limit switch blocks motion
  bool both_switches() const { return both_switches_; }
  // The torque limit in force for the last set-point, 0.1 % of rated torque.
  double torque_limit() const { return torque_limit_; }
  // Called by the engine when the loop saturated at the torque limit (bit 11 on A6B L10111-L10176).
  void note_torque_saturated(bool saturated) { internal_limit_ = internal_limit_ || saturated; }

private:
  bool soft_limits_active(const AxisSample& s, bool homed) const;

  const DriveContext& ctx_;
  ObjectRef<std::int32_t> min_, max_;
  ObjectRef<std::uint16_t> max_torque_, positive_torque_, negative_torque_;
  double peak_permille_ = 3000.0;
  bool internal_limit_ = false;
  bool switch_active_ = false;
  bool both_switches_ = false;
  double torque_limit_ = 0.0;
};

}  // namespace vdrive::drive
