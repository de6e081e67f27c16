#include "vdrive/drive/modes/cyclic_velocity_mode.hpp"

#include <algorithm>
#include <cmath>

#include "vdrive/drive/motion_ramp.hpp"

namespace vdrive::drive {

CyclicVelocityMode::CyclicVelocityMode(const DriveContext& ctx)
    : ctx_(ctx), target_(ctx.objects, 0x60FF), velocity_offset_(ctx.objects, 0x60B1),
      torque_offset_(ctx.objects, 0x60B2), max_motor_speed_(ctx.objects, 0x6080), cycle_(ctx.objects),
      halt_(ctx.objects) {}

std::int64_t CyclicVelocityMode::bus_target() const {
  std::int64_t t = target_.get();
  if (ctx_.profile.drive.offsets_honoured) t += velocity_offset_.get();
  return t;
}

double CyclicVelocityMode::max_speed() const {
  const std::uint32_t rpm = max_motor_speed_.get();
  return rpm == 0 ? -1.0 : std::abs(ctx_.units.rpm_to_user(static_cast<double>(rpm)));
}

void CyclicVelocityMode::restart_from(double velocity) {
  segment_.hold(velocity);
  output_ = velocity;
  halted_ = false;
  limited_ = false;
  // The first set-point is always taken, whatever its value.
  last_target_ = bus_target() + 1;
}

void CyclicVelocityMode::activate(const AxisSample& s) {
  restart_from(s.velocity_demand);
  cycle_.reset();
  status_ = 0;
}

void CyclicVelocityMode::idle(const AxisSample& s, std::uint16_t) {
  restart_from(s.velocity);
  cycle_.reset();
  status_ = 0;
}

Setpoint CyclicVelocityMode::step(const AxisSample& s, std::uint16_t controlword) {
  Setpoint sp;
  sp.kind = Setpoint::Kind::Velocity;
  sp.position = s.position;
  const std::int64_t target = bus_target();
  const double vmax = max_speed();

  if (controlword & cw::halt) {
    MotionState m{s.position, output_};
    m = ramp_velocity(m, 0.0, halt_.deceleration(), halt_.deceleration(), s.dt_s);
    output_ = m.velocity;
    segment_.hold(output_);
    cycle_.reset();
    last_target_ = target + 1;  // after the halt the next set-point is taken at once
    halted_ = true;
  } else {
    halted_ = false;
    Nanos at = 0;
    if (cycle_.take_new(target != last_target_, s.time, at)) {
      last_target_ = target;
      double goal = static_cast<double>(target);
      limited_ = vmax >= 0.0 && std::abs(goal) > vmax;
      if (limited_) goal = std::copysign(vmax, goal);
      segment_.start(segment_.value_at(at), goal, at, cycle_.period(), 0);
    }
    output_ = segment_.value_at(s.time);
    if (vmax >= 0.0) output_ = std::clamp(output_, -vmax, vmax);
  }
  sp.velocity = output_;
  if (ctx_.profile.drive.offsets_honoured) sp.torque = torque_offset_.get();
  status_ = halted_ ? 0 : sw::oms12;
  return sp;
}

}  // namespace vdrive::drive
