#include "vdrive/drive/modes/cyclic_position_mode.hpp"

#include <algorithm>
#include <cmath>

namespace vdrive::drive {

namespace {
// A late or lost set-point is bridged for at most two bus cycles (the A6B figure, L16888-L16917).
constexpr int kExtrapolatedCycles = 2;
// 607Ah is whole user units: a master stepping at exactly 6080h rounds up to one unit.
constexpr double kRoundingSlack = 1.0;
// 3722h bit 5: csp command change saturated at the 6080h limit (L16930-L16960).
constexpr std::int16_t kSaturateAtMaxSpeed = 1 << 5;
}  // namespace

CyclicPositionMode::CyclicPositionMode(const DriveContext& ctx)
    : ctx_(ctx), target_(ctx.objects, 0x607A), position_offset_(ctx.objects, 0x60B0),
      velocity_offset_(ctx.objects, 0x60B1), torque_offset_(ctx.objects, 0x60B2),
      max_motor_speed_(ctx.objects, 0x6080), saturation_setup_(ctx.objects, 0x3722), cycle_(ctx.objects),
      halt_(ctx.objects), following_error_(ctx.objects) {}

std::int64_t CyclicPositionMode::bus_target() const {
  std::int64_t t = target_.get();
  if (ctx_.profile.drive.offsets_honoured) t += position_offset_.get();
  return t;
}

double CyclicPositionMode::step_limit(Nanos period) const {
  const std::uint32_t rpm = max_motor_speed_.get();
  const bool saturating = ctx_.profile.drive.csp_clamps_to_max_speed || (saturation_setup_.get() & kSaturateAtMaxSpeed);
  // 6080h = 0: a saturating drive does not move at all (A6B L16995-L16996); others have no limit.
  if (rpm == 0) return saturating ? 0.0 : -1.0;
  return std::abs(ctx_.units.rpm_to_user(static_cast<double>(rpm))) * static_cast<double>(period) * 1e-9;
}

void CyclicPositionMode::restart_from(double position) {
  segment_.hold(position);
  goal_ = position;
  output_ = position;
  last_target_ = std::llround(position);
  halted_ = false;
  clamped_ = false;
}

void CyclicPositionMode::activate(const AxisSample& s) {
  restart_from(s.position_demand);
  cycle_.reset();
  following_error_.reset();
  pending_alarm_ = {};
  status_ = 0;
}

void CyclicPositionMode::idle(const AxisSample& s, std::uint16_t) {
  restart_from(s.position);
  cycle_.reset();
  following_error_.reset();
  pending_alarm_ = {};
  status_ = 0;
}

void CyclicPositionMode::take_set_point(Nanos at, std::int64_t target) {
  const Nanos period = cycle_.period();
  const double limit = step_limit(period);
  const double increment = static_cast<double>(target - last_target_);
  last_target_ = target;
  const bool alarm_product =
      !ctx_.profile.drive.csp_clamps_to_max_speed && !ctx_.profile.drive.alarms.position_command_jump.empty();
  if (alarm_product && !(saturation_setup_.get() & kSaturateAtMaxSpeed) && limit >= 0.0 &&
      std::abs(increment) > limit + kRoundingSlack)
    pending_alarm_ = ctx_.profile.drive.alarms.position_command_jump;
  // Head for the target, at most one limit per cycle from where the demand was heading.
  double next = static_cast<double>(target);
  clamped_ = false;
  if (limit >= 0.0 && std::abs(next - goal_) > limit + kRoundingSlack) {
    next = goal_ + std::copysign(limit, next - goal_);
    clamped_ = true;
  }
  goal_ = next;
  segment_.start(segment_.value_at(at), goal_, at, period, cycle_.driven() ? kExtrapolatedCycles * period : 0);
}

Setpoint CyclicPositionMode::step(const AxisSample& s, std::uint16_t controlword) {
  Setpoint sp;
  sp.kind = Setpoint::Kind::Position;
  const std::int64_t target = bus_target();

  if (controlword & cw::halt) {
    if (!halted_) halting_ = {output_, segment_.rate_at(s.time)};
    halted_ = true;
    halting_ = ramp_velocity(halting_, 0.0, halt_.deceleration(), halt_.deceleration(), s.dt_s);
    segment_.hold(halting_.position);
    goal_ = halting_.position;
    output_ = halting_.position;
    cycle_.reset();
    last_target_ = target;  // set-points during halt are not followed, nor judged as steps
    sp.position = output_;
    sp.velocity = halting_.velocity;
  } else {
    halted_ = false;
    Nanos at = 0;
    if (cycle_.take_new(target != last_target_, s.time, at)) take_set_point(at, target);
    output_ = segment_.value_at(s.time);
    sp.position = output_;
    sp.velocity = segment_.rate_at(s.time);
    if (ctx_.profile.drive.offsets_honoured) sp.velocity += velocity_offset_.get();
  }
  if (ctx_.profile.drive.offsets_honoured) sp.torque = torque_offset_.get();

  status_ = 0;
  if (!halted_) status_ |= sw::oms12;
  if (following_error_.update(s)) status_ |= sw::oms13;
  return sp;
}

}  // namespace vdrive::drive
