#include "vdrive/drive/motion_limits.hpp"

#include <algorithm>
#include <cmath>

namespace vdrive::drive {

MotionLimits::MotionLimits(const DriveContext& ctx)
    : ctx_(ctx), min_(ctx.objects, 0x607D, 1), max_(ctx.objects, 0x607D, 2), max_torque_(ctx.objects, 0x6072),
      positive_torque_(ctx.objects, 0x60E0), negative_torque_(ctx.objects, 0x60E1) {
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
  for (const auto* ref : {&positive_torque_, &negative_torque_})
    if (ref->present() && ref->get() > 0) limit = std::min(limit, double(ref->get()));
  if (ctx_.profile.drive.torque_clamp_permille > 0.0) limit = std::min(limit, ctx_.profile.drive.torque_clamp_permille);
  if (sp.torque_limit > 0.0) limit = std::min(limit, sp.torque_limit);
  torque_limit_ = limit;
  if (sp.kind == Setpoint::Kind::Torque && std::abs(sp.torque) > limit) {
    sp.torque = std::copysign(limit, sp.torque);
    internal_limit_ = true;
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

  // Software position limits: position demands are clamped into [min, max]; outside the range
  // only motion back toward it is allowed (A6B L13055-L13250, DS1000A-EC L1387-L1414).
  if (!homing && soft_limits_active(s, homed)) {
    const double lo = min_.get(), hi = max_.get();
    if (sp.kind == Setpoint::Kind::Position) {
      if (sp.position > hi && direction > 0.0) { sp.position = std::max(hi, s.position_demand); sp.velocity = 0.0; internal_limit_ = true; }
      if (sp.position < lo && direction < 0.0) { sp.position = std::min(lo, s.position_demand); sp.velocity = 0.0; internal_limit_ = true; }
    } else if ((s.position >= hi && direction > 0.0) || (s.position <= lo && direction < 0.0)) {
      block(sp);
    }
  }
  return sp;
}

}  // namespace vdrive::drive
