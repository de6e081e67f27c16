#pragma once
// The limits every set-point passes before the control loops: software position
// limits 607Dh on position set-points (profile.drive.soft_limits: always once referenced / only
// after homing / ignored; the A6B decelerates by 6085h from the limit, the others stop at it),
// limit switches (profile.drive.limit_switches: no motion into an active limit), and the torque
// limits in force: min(6072h, the product's clamp, the set-point's own limit) in both directions,
// 60E0h on the positive and 60E1h on the negative torque (A6B: with 3521h = 5). Reports
// statusword bit 11 "internal limit active" when any of them acted.
#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/drive_types.hpp"
#include "vdrive/drive/motion_ramp.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class MotionLimits {
public:
  explicit MotionLimits(const DriveContext& ctx);

  // `homing`: homing runs (it moves onto the switches on purpose; soft limits do not apply).
  // `homed`: a homing run completed since power-on.
  Setpoint apply(const Setpoint& sp, const AxisSample& s, bool homing, bool homed);

  bool internal_limit() const { return internal_limit_; }
  // The last position set-point was changed by a software limit (the mode's move was stopped).
  bool soft_limited() const { return soft_limited_; }
  bool limit_switch_active() const { return switch_active_; }   // a limit switch blocks motion
  bool both_switches() const { return both_switches_; }
  // The torque limits in force for the last set-point, 0.1 % of rated torque, on the motor side
  // (positive = the motor's positive direction): forward 60E0h, reverse 60E1h, each also capped by
  // 6072h, the product's clamp and the set-point's own limit.
  double torque_limit_forward() const { return torque_forward_; }
  double torque_limit_reverse() const { return torque_reverse_; }
  // Called by the engine when the loop saturated at the torque limit (bit 11 on A6B L10111-L10176).
  void note_torque_saturated(bool saturated) { internal_limit_ = internal_limit_ || saturated; }

private:
  bool soft_limits_active(const AxisSample& s, bool homed) const;

  const DriveContext& ctx_;
  ObjectRef<std::int32_t> min_, max_;
  ObjectRef<std::uint16_t> max_torque_, positive_torque_, negative_torque_;
  ObjectRef<std::int16_t> selection_;  // A6B 3521h torque limit selection; absent elsewhere
  ObjectRef<std::uint32_t> quick_stop_dec_;
  bool soft_limit_ramps_ = false;       // a software limit decelerates by 6085h instead of stopping at it
  double peak_permille_ = 3000.0;
  bool internal_limit_ = false;
  bool soft_limited_ = false;
  bool switch_active_ = false;
  bool both_switches_ = false;
  double torque_forward_ = 0.0, torque_reverse_ = 0.0;
  MotionState soft_ramp_{};     // where the A6B's 6085h ramp at a software limit left the demand
  bool soft_ramping_ = false;
};

}  // namespace vdrive::drive
