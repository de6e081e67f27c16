#include "vdrive/drive/modes/cyclic_torque_mode.hpp"

#include <algorithm>
#include <cmath>

namespace vdrive::drive {

namespace {
constexpr double kTaperBand = 0.05;  // of the cap: full torque at the cap, none 5 % above it
}

CyclicTorqueMode::CyclicTorqueMode(const DriveContext& ctx)
    : ctx_(ctx), target_(ctx.objects, 0x6071), torque_offset_(ctx.objects, 0x60B2),
      max_motor_speed_(ctx.objects, 0x6080), halt_(ctx.objects) {}

double CyclicTorqueMode::speed_cap() const {
  double rpm = static_cast<double>(max_motor_speed_.get());
  const double cap = ctx_.profile.drive.torque_mode_speed_cap_rpm;
  if (cap > 0.0) rpm = rpm > 0.0 ? std::min(rpm, cap) : cap;
  return rpm > 0.0 ? std::abs(ctx_.units.rpm_to_user(rpm)) : -1.0;
}

void CyclicTorqueMode::activate(const AxisSample& s) {
  output_ = s.torque_demand;
  halted_ = false;
  speed_limited_ = false;
  status_ = 0;
}

void CyclicTorqueMode::idle(const AxisSample&, std::uint16_t) {
  output_ = 0.0;
  halted_ = false;
  speed_limited_ = false;
  status_ = 0;
}

Setpoint CyclicTorqueMode::step(const AxisSample& s, std::uint16_t controlword) {
  Setpoint sp;
  sp.kind = Setpoint::Kind::Torque;
  sp.position = s.position;
  sp.velocity = s.velocity;

  halted_ = (controlword & cw::halt) != 0;
  if (halted_) {
    const double slope = halt_.torque_slope();
    output_ = slope <= 0.0 ? 0.0 : output_ - std::clamp(output_, -slope * s.dt_s, slope * s.dt_s);
    speed_limited_ = false;
  } else {
    double torque = target_.get();
    if (ctx_.profile.drive.offsets_honoured) torque += torque_offset_.get();
    const double cap = speed_cap();
    speed_limited_ = false;
    if (cap >= 0.0 && torque * s.velocity > 0.0 && std::abs(s.velocity) > cap) {
      const double over = (std::abs(s.velocity) - cap) / (kTaperBand * std::max(cap, 1e-9));
      torque *= std::clamp(1.0 - over, -1.0, 1.0);
      speed_limited_ = true;
    }
    output_ = torque;
  }
  sp.torque = output_;
  status_ = (halted_ || speed_limited_) ? 0 : sw::oms12;
  return sp;
}

}  // namespace vdrive::drive
