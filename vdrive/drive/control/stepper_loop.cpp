#include "vdrive/drive/control/stepper_loop.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vdrive::drive {

namespace {
constexpr double kRpm = 2.0 * std::numbers::pi / 60.0;
// 2113h CloseToOpenTime default (L4820); the profile's StepperSpec names no parameter for it.
constexpr double kStandstillBeforeOpen_s = 0.100;
// "Stood still": below the DS1000A-EC's slowest controlled speed, 6 r/min (L5659-L5670).
constexpr double kStillSpeed_rad_s = 6.0 * kRpm;
// Open/closed hysteresis around the switch speed, so that noise on the speed does not toggle it.
constexpr double kHysteresis = 0.05;
}  // namespace

StepperLoop::StepperLoop(const DriveContext& ctx, const plant::MotorParams& motor)
    : servo_(ctx, motor), loop_mode_(ctx.objects, ctx.profile.drive.stepper_loop.loop_mode),
      switch_speed_rpm_(ctx.objects, ctx.profile.drive.stepper_loop.switch_speed_rpm),
      run_current_(ctx.objects, ctx.profile.drive.stepper_loop.run_current) {}

void StepperLoop::reset(const plant::AxisFeedback& fb) {
  servo_.reset(fb);
  // 210Dh range 0..2 (L3915); anything else runs the factory setting, closed loop (L4808).
  const double m = loop_mode_.get(0.0);
  mode_ = m == 1.0 ? LoopMode::OpenBelowSwitchSpeed : m == 2.0 ? LoopMode::Open : LoopMode::Closed;
  switch_speed_rad_s_ = std::max(0.0, switch_speed_rpm_.get(0.0)) * kRpm;
  // Full rated current where the profile names no open-loop current.
  current_ = std::clamp(run_current_.get(1.0), 0.0, 1.0);
  still_s_ = 0.0;
  open_ = false;
}

bool StepperLoop::wants_open(const MotorSetpoint& sp, const plant::AxisFeedback& fb, double dt) {
  if (sp.kind != Setpoint::Kind::Position) return false;
  switch (mode_) {
    case LoopMode::Closed: return false;
    case LoopMode::Open: return true;
    case LoopMode::OpenBelowSwitchSpeed: break;
  }
  const double speed = std::abs(fb.motor_velocity_rad_s);
  if (switch_speed_rad_s_ <= 0.0) {
    const bool still = speed <= kStillSpeed_rad_s && std::abs(sp.velocity_rad_s) <= kStillSpeed_rad_s;
    still_s_ = still ? still_s_ + dt : 0.0;
    return open_ ? still : still_s_ >= kStandstillBeforeOpen_s;
  }
  const double band = kHysteresis * switch_speed_rad_s_;
  return open_ ? speed <= switch_speed_rad_s_ + band : speed <= switch_speed_rad_s_ - band;
}

plant::AxisCommand StepperLoop::step(const MotorSetpoint& sp, const plant::AxisFeedback& fb, double dt) {
  const bool open = wants_open(sp, fb, dt);
  if (open_ && !open) servo_.reset(fb);  // back to closed loop from where the rotor is
  open_ = open;
  if (!open) return servo_.step(sp, fb, dt);
  plant::AxisCommand cmd;
  cmd.stepper_open_loop = true;
  cmd.stepper_angle_rad = sp.angle_rad;
  cmd.stepper_current = current_;
  return cmd;
}

}  // namespace vdrive::drive
