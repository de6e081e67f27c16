#include "vdrive/drive/motion_limits.hpp"

#include <algorithm>
#include <cmath>

#include "vdrive/drive/motion_ramp.hpp"

namespace vdrive::drive {

MotionLimits::MotionLimits(const DriveContext& ctx)
    : ctx_(ctx), min_(ctx.objects, 0x607D, 1), max_(ctx.objects, 0x607D, 2), max_torque_(ctx.objects, 0x6072),
      positive_torque_(ctx.objects, 0x60E0), negative_torque_(ctx.objects, 0x60E1), selection_(ctx.objects, 0x3521),
      quick_stop_dec_(ctx.objects, 0x6085),
      // drive.soft_limits says when the limits act, drive.soft_limit_stop how they stop a move.
      soft_limit_ramps_(ctx.profile.drive.soft_limit_stop == profile::SoftLimitStop::Ramp) {
  const auto& motors = ctx.profile.motors;
  if (!motors.empty() && motors.front().rated_torque_nm > 0.0 && motors.front().peak_torque_nm > 0.0)
    peak_permille_ = 1000.0 * motors.front().peak_torque_nm / motors.front().rated_torque_nm;
}

bool MotionLimits::soft_limits_active(const AxisSample& s, bool homed) const {
  if (!min_.present() || min_.get() >= max_.get()) return false;  // min >= max disables them
  switch (ctx_.profile.drive.soft_limits) {
    case profile::SoftLimitRule::Always: return s.referenced;
    case profile::SoftLimitRule::AfterHoming: return homed;
    case profile::SoftLimitRule::Ignored: return false;
  }
  return false;
}

Setpoint MotionLimits::apply(const Setpoint& in, const AxisSample& s, bool homing, bool homed) {
  Setpoint sp = in;
  internal_limit_ = false;

  // Torque limit: the smallest of what is configured. 0 in 6072h would stop every motion; a
  // product that ships 0 there has it filled at power-on by the engine.
  double limit = peak_permille_;
  if (max_torque_.present() && max_torque_.get() > 0) limit = std::min(limit, double(max_torque_.get()));
  if (ctx_.profile.drive.torque_clamp_permille > 0.0) limit = std::min(limit, ctx_.profile.drive.torque_clamp_permille);
  if (sp.torque_limit > 0.0) limit = std::min(limit, sp.torque_limit);
  // 60E0h limits the positive torque only and 60E1h the negative torque only (A6B L12910-L12926,
  // DS5C1 P3-28/P3-29 forward/reverse L1691, DS1000A-EC CW/CCW side L3870-L3874); taking the
  // smaller of the two for both directions capped one direction by the other's limit. Both are
  // motor-side: 607Eh does not act on them (A6B L28993-L29003 lists the commands it acts on).
  // The A6B applies them only with 3521h = 5 (L12916, L12926).
  const bool directional = !selection_.present() || selection_.get() == 5;
  torque_forward_ = torque_reverse_ = limit;
  if (directional && positive_torque_.present() && positive_torque_.get() > 0)
    torque_forward_ = std::min(torque_forward_, double(positive_torque_.get()));
  if (directional && negative_torque_.present() && negative_torque_.get() > 0)
    torque_reverse_ = std::min(torque_reverse_, double(negative_torque_.get()));
  if (sp.kind == Setpoint::Kind::Torque) {
    const double sign = ctx_.units.torque_sign();  // user torque -> motor torque
    const double motor = sign * sp.torque;
    const double clamped = std::clamp(motor, -torque_reverse_, torque_forward_);
    if (clamped != motor) {
      sp.torque = sign * clamped;
      internal_limit_ = true;
    }
  }

  // Direction the set-point asks for.
  double direction = 0.0;
  switch (sp.kind) {
    case Setpoint::Kind::Position: direction = sp.position - s.position_demand; break;
    case Setpoint::Kind::Velocity: direction = sp.velocity; break;
    case Setpoint::Kind::Torque: direction = sp.torque; break;
  }
  auto block = [&](Setpoint& p) {
    switch (p.kind) {
      case Setpoint::Kind::Position: p.position = s.position_demand; p.velocity = 0.0; break;
      case Setpoint::Kind::Velocity: p.velocity = 0.0; break;
      case Setpoint::Kind::Torque: p.torque = 0.0; break;
    }
    internal_limit_ = true;
  };

  // Limit switches: no motion further into an active limit (homing drives onto them on purpose).
  const bool pos_switch = (s.inputs & din::positive_limit) != 0;
  const bool neg_switch = (s.inputs & din::negative_limit) != 0;
  both_switches_ = pos_switch && neg_switch;
  switch_active_ = false;
  if (!homing && ctx_.profile.drive.limit_switches != profile::LimitSwitchRule::ReportOnly) {
    if ((pos_switch && direction > 0.0) || (neg_switch && direction < 0.0)) {
      switch_active_ = true;
      block(sp);
    }
    if (pos_switch || neg_switch) internal_limit_ = true;
  }

  // Software position limits act on position control only: pp, ip, csp (A6B L13145; DS1000A-EC
  // "position control settings" 7.3, L1293/L1387). Velocity and torque set-points used to be
  // blocked at the limits too. Outside the range only motion back toward it is allowed, and bit 11
  // shows it until the axis is back inside (A6B L13161-L13167, DS1000A-EC L1402). A demand that
  // would pass a limit stops as the product does:
  //  - A6B: decelerating by the quick-stop ramp 6085h from where the limit is detected
  //    (L13212-L13218), so it stands beyond the limit by v^2 / (2 * 6085h);
  //  - DS1000A-EC: at the limit ("stops within the range", L1400).
  soft_limited_ = false;
  if (!homing && sp.kind == Setpoint::Kind::Position && soft_limits_active(s, homed)) {
    const double lo = min_.get(), hi = max_.get();
    const bool past_hi = sp.position > hi && direction > 0.0;
    const bool past_lo = sp.position < lo && direction < 0.0;
    if (past_hi || past_lo) {
      soft_limited_ = true;
      const double toward = past_hi ? 1.0 : -1.0;
      // 606Bh is the last step's mean speed: while the axis took the ramp's last set-point,
      // continue from the ramp's own end speed (else the ramp ran at half the rate).
      MotionState from{s.position_demand, s.velocity_demand};
      if (soft_ramping_ && soft_ramp_.position == s.position_demand) from.velocity = soft_ramp_.velocity;
      if (soft_limit_ramps_ && from.velocity * toward > 0.0) {
        const double dec = quick_stop_dec_.get() == 0 ? 1.0 : static_cast<double>(quick_stop_dec_.get());
        const MotionState next = ramp_velocity(from, 0.0, dec, dec, s.dt_s);
        sp.position = next.position;
        sp.velocity = next.velocity;
        soft_ramp_ = next;
        soft_ramping_ = true;
      } else if (soft_limit_ramps_) {
        sp.position = s.position_demand;  // stood: hold, no motion further out
        sp.velocity = 0.0;
      } else {
        sp.position = past_hi ? std::max(hi, s.position_demand) : std::min(lo, s.position_demand);
        sp.velocity = 0.0;
      }
    }
    if (soft_limited_ || s.position > hi || s.position < lo) internal_limit_ = true;
  }
  return sp;
}

}  // namespace vdrive::drive
