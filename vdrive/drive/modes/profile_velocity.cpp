#include "vdrive/drive/modes/profile_velocity.hpp"

#include <algorithm>
#include <cmath>

namespace vdrive::drive {

namespace {
constexpr Nanos ms(std::uint32_t v) { return static_cast<Nanos>(v) * 1'000'000; }
}  // namespace

ProfileVelocityMode::ProfileVelocityMode(const DriveContext& ctx)
    : ctx_(ctx), profile_(ctx), target_velocity_(ctx.objects, 0x60FF), velocity_offset_(ctx.objects, 0x60B1),
      velocity_window_(ctx.objects, 0x606D), velocity_threshold_(ctx.objects, 0x606F),
      velocity_window_time_(ctx.objects, 0x606E), velocity_threshold_time_(ctx.objects, 0x6070) {}

double ProfileVelocityMode::commanded() const {
  double v = static_cast<double>(target_velocity_.get());
  if (ctx_.profile.drive.offsets_honoured) v += static_cast<double>(velocity_offset_.get());
  return v;
}

void ProfileVelocityMode::activate(const AxisSample& s) {
  demand_ = {s.position_demand, s.velocity_demand};
  limit_ = profile_.velocity_limit();
  in_window_.reset();
  status_ = speed_bit_ ? sw::oms12 : 0;
}

void ProfileVelocityMode::update_speed_bit(const AxisSample& s) {
  const bool above = std::abs(s.velocity) > static_cast<double>(velocity_threshold_.get());
  // 1 at once when at or below 606Fh; 0 only after 6070h ms above it.
  speed_bit_ = !above_threshold_.update(above, s.time, ms(velocity_threshold_time_.get()));
}

Setpoint ProfileVelocityMode::step(const AxisSample& s, std::uint16_t controlword) {
  const bool halted = controlword & cw::halt;
  // 607Fh/6080h changes act only from standstill (A6B L21712-L21714).
  if (demand_.velocity == 0.0) limit_ = profile_.velocity_limit();
  const double target = commanded();
  const double goal = halted ? 0.0 : std::clamp(target, -limit_, limit_);
  const double dec = halted ? profile_.halt_deceleration() : profile_.deceleration();
  demand_ = ramp_velocity(demand_, goal, profile_.acceleration(), dec, s.dt_s);

  update_speed_bit(s);
  bool reached = false;
  if (halted) {  // halt: 1 once the axis stands (A6B L21500-L21507)
    in_window_.reset();
    reached = demand_.velocity == 0.0 && s.stopped;
  } else {
    // Compared with the commanded sum, not the limited one (A6B L21485-L21489).
    const bool inside = std::abs(target - s.velocity) <= static_cast<double>(velocity_window_.get());
    reached = in_window_.update(inside, s.time, ms(velocity_window_time_.get()));
  }
  status_ = static_cast<std::uint16_t>((reached ? sw::target_reached : 0) | (speed_bit_ ? sw::oms12 : 0));

  Setpoint sp;
  sp.kind = Setpoint::Kind::Velocity;
  sp.position = demand_.position;
  sp.velocity = demand_.velocity;
  return sp;
}

void ProfileVelocityMode::idle(const AxisSample& s, std::uint16_t /*controlword*/) {
  demand_ = {s.position, s.velocity};
  in_window_.reset();
  update_speed_bit(s);  // bit 12 tells standstill in every state
  status_ = speed_bit_ ? sw::oms12 : 0;
}

}  // namespace vdrive::drive
