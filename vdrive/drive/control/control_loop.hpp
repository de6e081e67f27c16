#pragma once
// The drive's inner loops: each control step (profile.drive.control_period_ns)
// they turn a motor-side set-point into what the power stage does to the motor, a plant
// AxisCommand. Independent of the bus cycle. Servos run position P -> velocity PI -> torque filter
// -> torque limit (ServoLoop); the DS1000A-EC closed-loop stepper runs the same cascade or drives
// the motor open loop (StepperLoop). Gains come from the product's own parameters
// (profile.drive.gains), read at reset(). step() allocates nothing.
#include <memory>

#include "plant/plant.hpp"
#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/drive_types.hpp"

namespace vdrive::drive {

// A Setpoint on the motor shaft. angle_rad is in the frame of plant::AxisFeedback::motor_angle_rad.
// Position: angle demand, velocity_rad_s and torque_nm are feed-forward. Velocity: velocity demand,
// torque_nm feed-forward. Torque: torque demand. torque_limit_nm <= 0: the motor's peak torque;
// it limits both directions unless torque_limit_reverse_nm > 0 limits the negative torque
// (60E0h/60E1h are separate limits per direction).
struct MotorSetpoint {
  Setpoint::Kind kind = Setpoint::Kind::Position;
  double angle_rad = 0.0;
  double velocity_rad_s = 0.0;
  double torque_nm = 0.0;
  double torque_limit_nm = 0.0;
  double torque_limit_reverse_nm = 0.0;
};

class ControlLoop {
public:
  virtual ~ControlLoop();
  // Power stage switches on (or the loop is re-armed): integrators and filters start from the
  // axis as it is, so enabling does not kick the motor; gains are (re)read from the parameters.
  virtual void reset(const plant::AxisFeedback& fb) = 0;
  virtual plant::AxisCommand step(const MotorSetpoint& sp, const plant::AxisFeedback& fb, double dt) = 0;
};

// The loop the product runs: StepperLoop when profile.drive.stepper or the motor is a stepper,
// else ServoLoop. Resolves its parameter handles from ctx.objects (construction time only).
std::unique_ptr<ControlLoop> make_control_loop(const DriveContext& ctx, const plant::MotorParams& motor);

}  // namespace vdrive::drive
