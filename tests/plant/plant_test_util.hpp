#pragma once
// Builders for single-axis test plants: a load on one joint driven by one motor.
#include "plant/plant.hpp"

namespace vdrive::plant::test {

// A motor with round numbers, so analytic results are easy to state.
inline MotorParams test_motor(double rotor_inertia = 1e-4) {
  MotorParams m;
  m.model = "test";
  m.rotor_inertia_kgm2 = rotor_inertia;
  m.torque_constant_nm_per_a = 0.5;
  m.rated_torque_nm = 2.0;
  m.peak_torque_nm = 6.0;
  m.rated_current_a = 4.0;
  m.max_speed_rad_s = 1e6;
  m.current_bandwidth_hz = 5000.0;
  return m;
}

// Direct-drive rotary inertia on a hinge about z (the axis's own load body).
inline PlantDescription rotary(double load_inertia, double rotor_inertia = 1e-4) {
  PlantDescription d;
  d.step_s = 250e-6;
  d.substeps = 4;
  AxisSpec a;
  a.name = "x";
  a.motor = test_motor(rotor_inertia);
  a.load_inertia_kgm2 = load_inertia;
  a.encoder.counts_per_rev = 10000;
  d.axes.push_back(a);
  return d;
}

// Runs `seconds` of plant time with a constant command.
inline void run(Plant& p, double seconds, const AxisCommand& cmd, std::size_t axis = 0) {
  p.command(axis, cmd);
  const auto steps = static_cast<long>(seconds / p.step_s() + 0.5);
  for (long i = 0; i < steps; ++i) p.step();
}

inline AxisCommand torque(double nm) {
  AxisCommand c;
  c.torque_nm = nm;
  return c;
}

}  // namespace vdrive::plant::test
