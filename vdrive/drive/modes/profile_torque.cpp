#include "vdrive/drive/modes/profile_torque.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vdrive::drive {

namespace {
// Leaving the speed limit needs the speed to fall this far below the cap, so the mode does not
// flip between torque and velocity control on the velocity loop's ripple.
constexpr double kSpeedLimitRelease = 0.9;
}  // namespace

ProfileTorqueMode::ProfileTorqueMode(const DriveContext& ctx)
    : ctx_(ctx), target_torque_(ctx.objects, 0x6071), torque_offset_(ctx.objects, 0x60B2),
      halt_option_(ctx.objects, 0x605D, 0, 1), torque_slope_(ctx.objects, 0x6087),
      max_motor_speed_(ctx.objects, 0x6080, 0, std::numeric_limits<std::uint32_t>::max()),
      max_torque_(ctx.objects, 0x6072, 0, std::numeric_limits<std::uint16_t>::max()) {}

double ProfileTorqueMode::commanded() const {
  double t = static_cast<double>(target_torque_.get());
  if (ctx_.profile.drive.offsets_honoured) t += static_cast<double>(torque_offset_.get());
  double limit = static_cast<double>(max_torque_.get());
  if (ctx_.profile.drive.torque_clamp_permille > 0.0) limit = std::min(limit, ctx_.profile.drive.torque_clamp_permille);
  return std::clamp(t, -limit, limit);
}

double ProfileTorqueMode::speed_cap() const {
  double cap = std::abs(ctx_.units.rpm_to_user(static_cast<double>(max_motor_speed_.get())));
  if (ctx_.profile.drive.torque_mode_speed_cap_rpm > 0.0)
    cap = std::min(cap, std::abs(ctx_.units.rpm_to_user(ctx_.profile.drive.torque_mode_speed_cap_rpm)));
  return cap;
}

void ProfileTorqueMode::activate(const AxisSample& s) {
  demand_ = s.torque_demand;
  speed_limited_ = false;
  status_ = 0;
}

Setpoint ProfileTorqueMode::step(const AxisSample& s, std::uint16_t controlword) {
  const bool halted = controlword & cw::halt;
  const double target = commanded();
  const double slope = torque_slope_.get() == 0 ? 1.0 : static_cast<double>(torque_slope_.get());
  if (halted && halt_option_.get() == 3) {
    demand_ = 0.0;  // zero torque at once
  } else {
    const double goal = halted ? 0.0 : target;
    const double dt_step = slope * s.dt_s;
    demand_ += std::clamp(goal - demand_, -dt_step, dt_step);
  }

  const double cap = speed_cap();
  const double v = s.velocity;
  const bool pushing = demand_ * v > 0.0;
  if (pushing && std::abs(v) >= cap) speed_limited_ = true;
  else if (!pushing || std::abs(v) < kSpeedLimitRelease * cap) speed_limited_ = false;

  const bool reached = halted ? s.stopped : demand_ == target;
  status_ = reached ? sw::target_reached : 0;

  Setpoint sp;
  if (speed_limited_) {
    sp.kind = Setpoint::Kind::Velocity;
    sp.position = s.position;
    sp.velocity = v > 0.0 ? cap : -cap;
    sp.torque_limit = std::max(std::abs(demand_), 1.0);
  } else {
    sp.kind = Setpoint::Kind::Torque;
    sp.position = s.position;
    sp.velocity = v;
    sp.torque = demand_;
  }
  return sp;
}

void ProfileTorqueMode::idle(const AxisSample& s, std::uint16_t /*controlword*/) {
  demand_ = s.torque;
  speed_limited_ = false;
  status_ = 0;
}

}  // namespace vdrive::drive
