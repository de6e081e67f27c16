#pragma once
// A mode's Setpoint (user units, 0.1 % of rated torque, after polarity) as the control loop's
// MotorSetpoint: through the unit scaling in force, from the motor angle where user position 0
// lies (`motor_zero_rad`, the engine's reference), with the torque limit in force (0.1 %, 0 = none;
// motor side) and, when given (> 0), a separate limit of the negative torque.
#include "vdrive/drive/control/control_loop.hpp"
#include "vdrive/drive/unit_scaling.hpp"

namespace vdrive::drive {

inline MotorSetpoint to_motor_setpoint(const Setpoint& sp, const UnitScaling& units, double rated_torque_nm,
                                       double motor_zero_rad, double torque_limit_permille,
                                       double reverse_torque_limit_permille = 0.0) {
  MotorSetpoint m;
  m.kind = sp.kind;
  m.angle_rad = motor_zero_rad + units.position_to_motor(sp.position);
  m.velocity_rad_s = units.velocity_to_motor(sp.velocity);
  m.torque_nm = units.torque_sign() * sp.torque * 1e-3 * rated_torque_nm;
  m.torque_limit_nm = torque_limit_permille > 0.0 ? torque_limit_permille * 1e-3 * rated_torque_nm : 0.0;
  m.torque_limit_reverse_nm =
      reverse_torque_limit_permille > 0.0 ? reverse_torque_limit_permille * 1e-3 * rated_torque_nm : 0.0;
  return m;
}

}  // namespace vdrive::drive
