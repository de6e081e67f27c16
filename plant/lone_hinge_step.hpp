#pragma once
// The ODE step (dWorldStep) of a lone rigid body on a hinge to the world, in closed form.
//
// Every drive's default plant is one such body: its own load inertia on a hinge through its centre
// of mass, about a principal axis. ODE spends about 2 us per step on it (island search, a 6-row LCP
// for five locked freedoms and the friction motor, quaternion update); its result reduces to:
//   - the velocity step, semi-implicit Euler: v_free = v + h * torque / J;
//   - the friction motor (target speed 0, force limit `dry`) as the LCP's one bounded row:
//     lambda = clamp(-J * v_free / h, -dry, dry), v = v_free + h * lambda / J;
//   - the angle step ODE's quaternion update takes (q += h/2 * w * q, then normalised), which turns
//     the body by 2 atan(v h / 2), not by v h.
// The locked freedoms carry no load (no gravity torque about the centre, no gyroscopic torque about
// a principal axis) and ODE's constraint-force mixing (1e-10) changes lambda by ~1e-10 relative, so
// the two agree to rounding (tests/plant/closed_form_hinge_test.cpp steps both side by side).
#include <algorithm>
#include <cmath>

namespace vdrive::plant {

// One step of h seconds: `angle` (rad, continuous) and `velocity` (rad/s) of a body of `inertia`
// (kg m^2, about the hinge) under `torque` (N m) and dry friction up to `dry` (N m).
inline void lone_hinge_step(double& angle, double& velocity, double inertia, double torque, double dry,
                            double h) {
  const double free = velocity + h * torque / inertia;
  double v = free;
  if (dry > 0) {
    const double lambda = std::clamp(-inertia * free / h, -dry, dry);
    v = free + h * lambda / inertia;
  }
  velocity = v;
  angle += 2.0 * std::atan(0.5 * v * h);
}

}  // namespace vdrive::plant
