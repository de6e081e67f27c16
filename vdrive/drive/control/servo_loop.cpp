#include "vdrive/drive/control/servo_loop.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vdrive::drive {

ServoLoop::ServoLoop(const DriveContext& ctx, const plant::MotorParams& motor)
    : source_(ctx, motor), gains_(source_.read()),
      peak_torque_nm_(motor.peak_torque_nm > 0.0 ? motor.peak_torque_nm : motor.rated_torque_nm) {}

void ServoLoop::reset(const plant::AxisFeedback& fb) {
  gains_ = source_.read();
  integral_ = 0.0;
  // The current loop holds what it delivers now (0 when the stage was off): no step on enable.
  filtered_ = fb.torque_nm;
  torque_ = fb.torque_nm;
  saturated_ = false;
  have_ff_ = false;
  // The filter state alone would decay to the PI's demand (0 with an empty integrator) within a
  // few periods: the first position/velocity step presets the integrator to the delivered torque,
  // as on leaving torque control (the bumpless entry in step()).
  last_kind_ = Setpoint::Kind::Torque;
}

plant::AxisCommand ServoLoop::step(const MotorSetpoint& sp, const plant::AxisFeedback& fb, double dt) {
  const double limit = sp.torque_limit_nm > 0.0 ? std::min(sp.torque_limit_nm, peak_torque_nm_) : peak_torque_nm_;
  const double reverse_limit =
      sp.torque_limit_reverse_nm > 0.0 ? std::min(sp.torque_limit_reverse_nm, peak_torque_nm_) : limit;
  const double kv = gains_.velocity_gain;
  const bool integrating = gains_.velocity_integral_s > 0.0;

  double demand = sp.torque_nm;
  double velocity_error = 0.0;
  if (sp.kind != Setpoint::Kind::Torque) {
    // Bumpless entry from torque control: the PI starts out delivering the present torque.
    if (last_kind_ == Setpoint::Kind::Torque && integrating && kv > 0.0) integral_ = (torque_ - sp.torque_nm) / kv;
    double w_ref = sp.velocity_rad_s;
    double acceleration_ff = 0.0;
    if (sp.kind == Setpoint::Kind::Position) {
      w_ref = gains_.position_gain * (sp.angle_rad - fb.motor_angle_rad) + gains_.velocity_feedforward * sp.velocity_rad_s;
      // The torque the commanded acceleration needs, fed forward in the same proportion as the
      // speed: with full feed-forward the position loop only corrects disturbances.
      // J_tot = Kv / (2 pi f_v) (control_gains.hpp).
      if (have_ff_ && dt > 0.0 && gains_.velocity_bandwidth_hz > 0.0) {
        const double inertia = kv / (2.0 * std::numbers::pi * gains_.velocity_bandwidth_hz);
        acceleration_ff = gains_.velocity_feedforward * inertia * (sp.velocity_rad_s - last_ff_velocity_) / dt;
      }
      last_ff_velocity_ = sp.velocity_rad_s;
      have_ff_ = true;
    } else {
      have_ff_ = false;
    }
    velocity_error = w_ref - fb.motor_velocity_rad_s;
    demand = kv * (velocity_error + integral_) + sp.torque_nm + acceleration_ff;
  }
  last_kind_ = sp.kind;

  const double k = gains_.torque_filter_s > 0.0 ? 1.0 - filter_exp_(-dt / gains_.torque_filter_s) : 1.0;
  filtered_ += (demand - filtered_) * k;
  torque_ = std::clamp(filtered_, -reverse_limit, limit);
  saturated_ = demand > limit || demand < -reverse_limit;
  // A filter state beyond the limit would only delay leaving it.
  filtered_ = std::clamp(filtered_, -reverse_limit, limit);

  if (sp.kind != Setpoint::Kind::Torque && integrating) {
    const bool winding_up = saturated_ && velocity_error * demand > 0.0;
    if (!winding_up) integral_ += velocity_error * dt / gains_.velocity_integral_s;
  } else {
    integral_ = 0.0;
  }

  plant::AxisCommand cmd;
  cmd.torque_nm = torque_;
  return cmd;
}

}  // namespace vdrive::drive
