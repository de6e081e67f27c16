#pragma once
// Carries out a stop (StopKind) as one set-point per control step, from where the demand is
// (s.position_demand / s.velocity_demand / s.torque_demand of the previous step) to standstill:
//   speed ramps  SlowDown 6084h (hm: 609Ah), QuickStopRamp 6085h, CurrentLimit 60C6h, in user
//                units/s^2; a value of 0 acts as 1 (A6B L26360-L26428, DS5C1 L4400-L4411).
//                Position modes get Position set-points (the axis holds where the ramp ends),
//                pv/csv Velocity set-points.
//   torque modes tq/cst ramp their torque to 0 with 6087h (0.1 %/s, 0 acts as 1) for every ramp
//                code, or drop it to 0 at once (ZeroTorque) (A6B L27045-L27057, DS5C1 L4420).
//   Coast and the servo-side free run / dynamic brake: torque 0, the power stage is off.
//   DriveSide Decelerate (DS5C1 P0-31) and ImmediateStop (A6B 3511h torque) as VendorStop says.
// The stop is done once the actual speed is at most profile.drive.stopped_speed_rpm (A6B 30 r/min
// L27098, DS5C1 10 r/min L4428). Decelerations are latched by start(); step() allocates nothing.
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/drive_types.hpp"
#include "vdrive/drive/motion_ramp.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/drive/pds/stop_kind.hpp"
#include "vdrive/drive/pds/vendor_stop.hpp"

namespace vdrive::drive {

class StopSequence {
public:
  explicit StopSequence(const DriveContext& ctx);

  // Latches the ramp for `kind` in mode `mode` (6061h). For DriveSide, `drive_side` is what
  // PdsMachine::drive_side_action() reports; None reads the servo-off sequence here.
  void start(StopKind kind, std::int8_t mode, const AxisSample& s,
             DriveSideAction drive_side = DriveSideAction::None);
  Setpoint step(const AxisSample& s);
  bool done(const AxisSample& s) const { return stopped(s.velocity); }

  // |velocity| (user units/s) at or below the product's "stopped" speed.
  bool stopped(double velocity) const;
  double stopped_speed() const;                                // user units/s
  StopKind kind() const { return kind_; }
  DriveSideAction drive_side_action() const { return action_; }
  // The latched rate: user units/s^2 for speed ramps, 0.1 %/s for torque ramps, 0 otherwise.
  double rate() const { return rate_; }

private:
  enum class Shape : std::uint8_t { Hold, SpeedRamp, TorqueRamp, Free, Immediate };

  const DriveContext& ctx_;
  VendorStop vendor_;
  ObjectRef<std::uint32_t> profile_dec_, quick_stop_dec_, max_dec_, homing_acc_, torque_slope_;
  StopKind kind_ = StopKind::None;
  DriveSideAction action_ = DriveSideAction::None;
  Shape shape_ = Shape::Hold;
  bool position_setpoints_ = true;
  double rate_ = 0.0;
  double torque_limit_ = 0.0;
  MotionState ramp_{};       // where the speed ramp left the demand (position set-points)
  bool ramping_ = false;
};

}  // namespace vdrive::drive
