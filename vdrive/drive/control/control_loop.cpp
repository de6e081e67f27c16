#include "vdrive/drive/control/control_loop.hpp"

#include "vdrive/drive/control/servo_loop.hpp"
#include "vdrive/drive/control/stepper_loop.hpp"

namespace vdrive::drive {

ControlLoop::~ControlLoop() = default;

std::unique_ptr<ControlLoop> make_control_loop(const DriveContext& ctx, const plant::MotorParams& motor) {
  if (ctx.profile.drive.stepper || motor.kind == plant::MotorKind::stepper)
    return std::make_unique<StepperLoop>(ctx, motor);
  return std::make_unique<ServoLoop>(ctx, motor);
}

}  // namespace vdrive::drive
