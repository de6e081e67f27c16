#pragma once
// The servo cascade: position P (with velocity and acceleration feed-forward, both scaled by the
// velocity feed-forward gain) -> velocity PI -> first-order torque command filter -> torque limit. Velocity and Torque set-points enter further down the chain.
// Anti-windup: the integrator holds while the limit clips in the direction it would grow.
// Changing the set-point kind is bumpless: entering the velocity loop from torque control
// presets the integrator to the torque being delivered; so does the first step after reset(fb),
// which starts from the torque the axis delivers (fb.torque_nm, 0 when the stage was off).
#include "common/cached_exp.hpp"
#include "vdrive/drive/control/control_gains.hpp"
#include "vdrive/drive/control/control_loop.hpp"

namespace vdrive::drive {

class ServoLoop final : public ControlLoop {
public:
  ServoLoop(const DriveContext& ctx, const plant::MotorParams& motor);

  void reset(const plant::AxisFeedback& fb) override;
  plant::AxisCommand step(const MotorSetpoint& sp, const plant::AxisFeedback& fb, double dt) override;

  const ControlGains& gains() const { return gains_; }
  bool saturated() const { return saturated_; }   // the last step clipped at the torque limit
  double torque_command_nm() const { return torque_; }

private:
  ControlGainSource source_;
  ControlGains gains_;
  double peak_torque_nm_;
  double integral_ = 0.0;   // integral of the velocity error over Ti, rad/s
  double filtered_ = 0.0;   // torque filter state, N m
  CachedExp filter_exp_;
  double torque_ = 0.0;     // last output, N m
  bool saturated_ = false;
  Setpoint::Kind last_kind_ = Setpoint::Kind::Position;
  double last_ff_velocity_ = 0.0;  // previous position set-point's feed-forward speed, rad/s
  bool have_ff_ = false;
};

}  // namespace vdrive::drive
