#pragma once
// The two motion primitives every mode and stop sequence is built from, stepped once per control
// period: a velocity ramp (pv, halt, stops, homing searches) and an online trapezoidal move to a
// target position that may change at any step (pp, homing moves). Both are pure and allocate nothing.
#include <algorithm>
#include <cmath>

namespace vdrive::drive {

struct MotionState {
  double position = 0.0;
  double velocity = 0.0;
};

// Moves `velocity` toward `target` by at most acc*dt (speeding up) or dec*dt (slowing down) and
// integrates position (trapezoid rule). acc/dec <= 0 are treated as "instantaneous".
inline MotionState ramp_velocity(MotionState s, double target, double acc, double dec, double dt) {
  const double v0 = s.velocity;
  const bool slowing = std::abs(target) < std::abs(v0) || (target * v0 < 0.0);
  const double rate = slowing ? dec : acc;
  double v = target;
  if (rate > 0.0) {
    const double dv = rate * dt;
    v = v0 + std::clamp(target - v0, -dv, dv);
  }
  s.position += 0.5 * (v0 + v) * dt;
  s.velocity = v;
  return s;
}

// One step of a time-optimal trapezoid toward `target` with speed limit vmax, acceleration acc and
// deceleration dec (all > 0). Ends exactly on the target with zero velocity. The step that would
// overshoot lands on the target instead, so the move never oscillates around it.
inline MotionState move_to(MotionState s, double target, double vmax, double acc, double dec, double dt) {
  const double remaining = target - s.position;
  if (std::abs(remaining) < 1e-12 && std::abs(s.velocity) * dt < 1e-12) return {target, 0.0};
  const double dir = remaining >= 0.0 ? 1.0 : -1.0;
  const double v_along = s.velocity * dir;  // speed toward the target (negative = moving away)
  // Speed we may still have and stop on the target: v^2 = 2 dec d.
  const double v_stop = std::sqrt(2.0 * dec * std::abs(remaining));
  double v_target = std::min(vmax, v_stop);
  if (v_along < 0.0) v_target = 0.0;  // moving away: brake first
  MotionState next = ramp_velocity({s.position, v_along}, v_target, acc, dec, dt);
  next.position = s.position + (next.position - s.position) * dir;
  next.velocity *= dir;
  const double after = target - next.position;
  if (after * remaining <= 0.0 || (std::abs(after) < std::abs(next.velocity) * dt * 0.5 && v_stop < dec * dt))
    return {target, 0.0};
  return next;
}

}  // namespace vdrive::drive
