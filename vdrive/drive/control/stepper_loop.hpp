#pragma once
// The DS1000A-EC closed-loop stepper (digest §9.3, manual 11.1.1 L4040-L4092): the loop mode
// parameter (210Dh "OpenModeSwitch", profile.drive.stepper_loop.loop_mode) selects
//   0  always closed loop: the servo cascade drives the motor through a torque demand;
//   1  open loop at or below the switch speed (210Eh), closed loop above it; with switch speed
//      0, open loop once the motor has stood still for 2113h (CloseToOpenTime, 100 ms default,
//      L4087-L4092, L4820);
//   2  always open loop: micro-stepping, the drive imposes the set-point angle with the open-loop
//      current (2112h, profile.drive.stepper_loop.run_current) and has no torque feedback.
// The mode applies to positioning ("位置決め時モード", L4040): velocity and torque set-points always
// run closed loop. Leaving open loop re-arms the cascade from the axis as it is (bumpless).
#include "vdrive/drive/control/control_loop.hpp"
#include "vdrive/drive/parameter_value.hpp"
#include "vdrive/drive/control/servo_loop.hpp"

namespace vdrive::drive {

class StepperLoop final : public ControlLoop {
public:
  enum class LoopMode : int { Closed = 0, OpenBelowSwitchSpeed = 1, Open = 2 };

  StepperLoop(const DriveContext& ctx, const plant::MotorParams& motor);

  void reset(const plant::AxisFeedback& fb) override;
  plant::AxisCommand step(const MotorSetpoint& sp, const plant::AxisFeedback& fb, double dt) override;

  LoopMode loop_mode() const { return mode_; }
  bool open_loop() const { return open_; }   // the last step ran open loop
  const ServoLoop& closed_loop() const { return servo_; }

private:
  bool wants_open(const MotorSetpoint& sp, const plant::AxisFeedback& fb, double dt);

  ServoLoop servo_;
  ParameterValue loop_mode_, switch_speed_rpm_, run_current_;
  LoopMode mode_ = LoopMode::Closed;
  double switch_speed_rad_s_ = 0.0;
  double current_ = 1.0;
  double still_s_ = 0.0;     // how long the motor has stood still (switch speed 0)
  bool open_ = false;
};

}  // namespace vdrive::drive
