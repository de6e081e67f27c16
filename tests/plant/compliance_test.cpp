// Compliant coupling (two-mass system) and backlash, against the analytic results:
// resonance w = sqrt(k (1/J_motor' + 1/J_load)) with J_motor' = J_rotor / r^2, and a dead zone of
// exactly the configured width between the motor and load sides.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "plant/plant.hpp"
#include "tests/plant/plant_test_util.hpp"

namespace vdrive::plant {
namespace {

using test::rotary;
using test::run;
using test::torque;

// Frequency of a sampled signal from its upward zero crossings (linear interpolation).
double frequency_hz(const std::vector<double>& x, double dt) {
  std::vector<double> crossings;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < 0 && x[i] >= 0) crossings.push_back((i - 1 + x[i - 1] / (x[i - 1] - x[i])) * dt);
  if (crossings.size() < 2) return 0;
  return (crossings.size() - 1) / (crossings.back() - crossings.front());
}

TEST(PlantCompliance, TwoMassResonanceMatchesTheAnalyticFrequency) {
  const double jr = 1e-4, jl = 4e-4, k = 50.0;
  PlantDescription d = rotary(jl, jr);
  d.axes[0].transmission.stiffness = k;
  Plant p(d);
  // A short torque pulse, then free oscillation of motor against load.
  run(p, 0.002, torque(1.0));
  std::vector<double> twist;
  AxisCommand none;
  p.command(0, none);
  for (int i = 0; i < 4000; ++i) {  // 1 s
    p.step();
    twist.push_back(p.feedback(0).motor_angle_rad - p.feedback(0).load_position);
  }
  const double expected = std::sqrt(k * (1 / jr + 1 / jl)) / (2 * M_PI);  // 125.8 Hz
  EXPECT_NEAR(frequency_hz(twist, p.step_s()), expected, 0.02 * expected);
}

TEST(PlantCompliance, TwoMassResonanceThroughAGearbox) {
  const double jr = 2e-5, jl = 0.02, k = 400.0, n = 8.0;
  PlantDescription d = rotary(jl, jr);
  d.axes[0].transmission.kind = TransmissionKind::gearbox;
  d.axes[0].transmission.ratio = n;
  d.axes[0].transmission.stiffness = k;  // at the load side
  Plant p(d);
  run(p, 0.002, torque(0.5));
  std::vector<double> twist;
  p.command(0, AxisCommand{});
  for (int i = 0; i < 4000; ++i) {
    p.step();
    twist.push_back(p.feedback(0).motor_angle_rad / n - p.feedback(0).load_position);
  }
  const double expected = std::sqrt(k * (1 / (jr * n * n) + 1 / jl)) / (2 * M_PI);
  EXPECT_NEAR(frequency_hz(twist, p.step_s()), expected, 0.02 * expected);
}

// The coupling spring is integrated by ODE's semi-implicit Euler (a leapfrog): no drift, and the
// energy (read at the half step, Plant::energy) stays within 1 % for the whole 10 s.
TEST(PlantCompliance, TwoMassEnergyIsConservedWithoutDamping) {
  PlantDescription d = rotary(4e-4, 1e-4);
  d.axes[0].transmission.stiffness = 50.0;
  Plant p(d);
  run(p, 0.002, torque(1.0));
  run(p, 0.002, AxisCommand{});  // let the current decay to zero before taking the reference
  const double e0 = p.energy();
  ASSERT_GT(e0, 0.0);
  double worst = 0, first_second = 0, last_second = 0;
  for (int i = 0; i < 40000; ++i) {  // 10 s
    p.step();
    const double e = p.energy();
    worst = std::max(worst, std::abs(e - e0));
    if (i < 4000) first_second += e / 4000;
    if (i >= 36000) last_second += e / 4000;
  }
  EXPECT_LT(worst, 0.01 * e0);
  EXPECT_NEAR(last_second, first_second, 0.001 * e0);  // no secular drift
}

TEST(PlantCompliance, BacklashDeadZoneHasTheConfiguredWidth) {
  const double b = 0.02, k = 100.0, t = 0.01;
  PlantDescription d = rotary(1e-3, 1.4e-5);
  d.axes[0].transmission.backlash = b;
  d.axes[0].transmission.stiffness = k;
  d.axes[0].transmission.damping = 0.05;
  d.axes[0].friction.breakaway = d.axes[0].friction.coulomb = 0.5;  // the load stays put
  Plant p(d);
  // Inside the dead zone the motor turns freely and the load does not follow.
  run(p, 0.005, torque(t));
  EXPECT_GT(p.feedback(0).motor_angle_rad, 0.0);
  EXPECT_EQ(p.feedback(0).load_position, 0.0);
  run(p, 1.0, torque(t));
  const double forward = p.feedback(0).motor_angle_rad;
  run(p, 1.0, torque(-t));
  const double backward = p.feedback(0).motor_angle_rad;
  EXPECT_LT(std::abs(p.feedback(0).load_position), 1e-9);
  // Resting against either flank, the spring is compressed by t/k in each direction.
  EXPECT_NEAR(forward - backward - 2 * t / k, b, 0.01 * b);
}

}  // namespace
}  // namespace vdrive::plant
