#pragma once
// The motor's electromagnetic torque, as pure functions of its state.
//  * Servo: the drive's current loop is a first-order lag of the configured bandwidth (exact step),
//    the command is clamped to peak torque, and torque tapers to zero between max speed and 110 %
//    of it (the supply voltage can no longer drive current against the back-EMF).
//  * Stepper in open loop: the drive imposes a current vector at electrical angle teeth*theta_cmd;
//    torque = -T_hold * (i/i_rated) * sin(teeth * (theta - theta_cmd)). If the load needs more than
//    the peak of that sine, the rotor slips to another equilibrium: whole electrical cycles (4 full
//    steps each) are lost.
#include <algorithm>
#include <cmath>

#include "plant/plant_description.hpp"

namespace vdrive::plant {

// Current after one step of length dt from `current` towards `command` (first-order lag); `exp`
// is the caller's exp, e.g. a CachedExp (common/cached_exp.hpp).
template <typename Exp>
double current_loop_step(double current, double command, double bandwidth_hz, double dt, Exp&& exp) {
  const double k = 1.0 - exp(-2.0 * M_PI * bandwidth_hz * dt);
  return current + (command - current) * k;
}

// Fraction of torque still available at motor speed w (1 below max speed, 0 above 110 %), applied
// only when the torque would accelerate further in the direction of motion.
inline double speed_taper(double torque, double w, double max_speed) {
  if (max_speed <= 0 || torque * w <= 0) return 1.0;
  const double over = (std::abs(w) - max_speed) / (0.1 * max_speed);
  return std::clamp(1.0 - over, 0.0, 1.0);
}

inline double stepper_torque(double holding_nm, double current_fraction, int teeth, double theta,
                             double theta_cmd) {
  return -holding_nm * current_fraction * std::sin(teeth * (theta - theta_cmd));
}

// Full steps the rotor lags behind the command, counted in whole electrical cycles (4 steps each):
// 0 while the rotor is within half a cycle of where it should be.
inline long stepper_lost_steps(int teeth, double theta, double theta_cmd) {
  const double cycles = teeth * (theta_cmd - theta) / (2.0 * M_PI);
  return 4 * std::lround(cycles);
}

}  // namespace vdrive::plant
