#include "vdrive/drive/control/control_gains.hpp"

#include <algorithm>
#include <numbers>

namespace vdrive::drive {

ControlGainSource::ControlGainSource(const DriveContext& ctx, const plant::MotorParams& motor)
    : rotor_inertia_(motor.rotor_inertia_kgm2 > 0.0 ? motor.rotor_inertia_kgm2 : 1e-5),
      kp_(ctx.objects, ctx.profile.drive.gains.position_gain),
      fv_(ctx.objects, ctx.profile.drive.gains.velocity_gain),
      ti_(ctx.objects, ctx.profile.drive.gains.velocity_integral),
      tf_(ctx.objects, ctx.profile.drive.gains.torque_filter),
      ratio_(ctx.objects, ctx.profile.drive.gains.inertia_ratio),
      kff_(ctx.objects, ctx.profile.drive.gains.velocity_feedforward) {}

ControlGains ControlGainSource::read() const {
  namespace d = engine_default_gains;
  ControlGains g;
  // A gain that must be positive and reads <= 0 (parameter absent, profile without fallback)
  // falls back to the engine default rather than switching the loop off.
  g.position_gain = kp_.get(d::position_gain);
  if (g.position_gain <= 0.0) g.position_gain = d::position_gain;
  g.velocity_bandwidth_hz = fv_.get(d::velocity_bandwidth_hz);
  if (g.velocity_bandwidth_hz <= 0.0) g.velocity_bandwidth_hz = d::velocity_bandwidth_hz;
  g.velocity_integral_s = ti_.get(d::velocity_integral_s);
  g.torque_filter_s = tf_.get(d::torque_filter_s);
  g.inertia_ratio = std::max(0.0, ratio_.get(d::inertia_ratio));
  g.velocity_feedforward = std::clamp(kff_.get(d::velocity_feedforward), 0.0, 1.0);
  g.velocity_gain = rotor_inertia_ * (1.0 + g.inertia_ratio) * 2.0 * std::numbers::pi * g.velocity_bandwidth_hz;
  return g;
}

}  // namespace vdrive::drive
