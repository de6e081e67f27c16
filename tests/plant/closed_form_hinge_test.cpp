// The closed-form step of a lone hinge (plant/lone_hinge_step.hpp) against ODE stepping the same
// world (PlantDescription::closed_form_hinges = false), side by side under one command sequence:
// acceleration, stick-slip around breakaway, the brake, a load profile, a gearbox, load change,
// and jam and obstacle faults (which hand the joint to ODE and back).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "plant/plant.hpp"
#include "tests/plant/plant_test_util.hpp"

namespace vdrive::plant {
namespace {

using test::rotary;

struct Deviation {
  double position = 0, velocity = 0, energy = 0;
};

// Runs `seconds` on both plants with the command `at(t)` and faults applied by `faults(step)`.
Deviation run_pair(const PlantDescription& d, double seconds, const std::function<AxisCommand(double)>& at,
                   const std::function<void(long, Plant&)>& faults = nullptr) {
  PlantDescription ode_only = d;
  ode_only.closed_form_hinges = false;
  Plant closed(d), ode(ode_only);
  Deviation dev;
  const auto steps = static_cast<long>(seconds / d.step_s + 0.5);
  for (long k = 0; k < steps; ++k) {
    const AxisCommand c = at(static_cast<double>(k) * d.step_s);
    closed.command(0, c);
    ode.command(0, c);
    if (faults) {
      faults(k, closed);
      faults(k, ode);
    }
    closed.step();
    ode.step();
    const AxisFeedback &a = closed.feedback(0), &b = ode.feedback(0);
    dev.position = std::max(dev.position, std::abs(a.load_position - b.load_position));
    dev.velocity = std::max(dev.velocity, std::abs(a.load_velocity - b.load_velocity));
    dev.energy = std::max(dev.energy, std::abs(closed.energy() - ode.energy()));
    EXPECT_EQ(a.faults, b.faults) << "step " << k;
    EXPECT_EQ(a.encoder.counts, b.encoder.counts) << "step " << k;
    if (a.encoder.counts != b.encoder.counts) break;
  }
  return dev;
}

AxisCommand torque_at(double t) {
  AxisCommand c;
  // Up through breakaway, a reversal, then long holds below breakaway (sticking).
  c.torque_nm = t < 0.3 ? 0.8 * std::sin(20 * t) : t < 0.6 ? -0.6 : 0.1 * std::sin(3 * t);
  c.brake_released = !(t > 0.8 && t < 0.9);
  return c;
}

PlantDescription frictional() {
  PlantDescription d = rotary(3e-4);
  d.axes[0].friction = {.coulomb = 0.15, .breakaway = 0.2, .stribeck_velocity = 0.5, .viscous = 1e-3};
  d.axes[0].brake = {.fitted = true, .holding_torque_nm = 0.5};
  d.axes[0].load_profile = {{0.0, 0.0}, {0.5, 0.05}, {1.0, -0.05}};
  return d;
}

TEST(ClosedFormHinge, FollowsOdeThroughFrictionBrakeAndLoadProfile) {
  const Deviation dev = run_pair(frictional(), 1.0, torque_at);
  EXPECT_LT(dev.position, 1e-9);
  EXPECT_LT(dev.velocity, 1e-7);
  EXPECT_LT(dev.energy, 1e-9);
}

TEST(ClosedFormHinge, FollowsOdeThroughAGearboxAtSpeed) {
  PlantDescription d = rotary(0.05, 1e-4);
  d.axes[0].transmission.kind = TransmissionKind::gearbox;
  d.axes[0].transmission.ratio = 10.0;
  // Hundreds of rad/s at the motor: ODE's angle step 2 atan(w h / 2) differs from w h here.
  const Deviation dev = run_pair(d, 1.0, [](double t) {
    AxisCommand c;
    c.torque_nm = t < 0.7 ? 3.0 : -3.0;
    return c;
  });
  EXPECT_LT(dev.position, 1e-9);
  EXPECT_LT(dev.velocity, 1e-7);
}

TEST(ClosedFormHinge, HandsOverToOdeForJamObstacleAndLoadChangeAndBack) {
  const long s = 4000;  // steps per second at 250 us
  const Deviation dev = run_pair(frictional(), 2.0, [](double t) {
    AxisCommand c;
    c.torque_nm = t < 1.2 ? 0.6 : -0.6;
    return c;
  }, [&](long k, Plant& p) {
    if (k == s / 5) p.set_axis_faults(0, {.jam = true});           // seized many turns out
    if (k == 2 * s / 5) p.set_axis_faults(0, {});                  // released: closed form again
    if (k == 3 * s / 5) p.set_axis_faults(0, {.load_scale = 3.0});
    if (k == 4 * s / 5) {                                          // an obstacle ahead
      AxisFaults f{.load_scale = 3.0};
      f.obstacle = p.feedback(0).load_position + 2.0;
      p.set_axis_faults(0, f);
    }
    if (k == 6 * s / 5) p.set_axis_faults(0, {});
  });
  EXPECT_LT(dev.position, 1e-9);
  EXPECT_LT(dev.velocity, 1e-7);
  EXPECT_LT(dev.energy, 1e-9);
}

TEST(ClosedFormHinge, JamStillHoldsWhenItBeginsInClosedForm) {
  Plant p(frictional());
  test::run(p, 0.3, test::torque(0.6));
  const double seized = p.feedback(0).load_position;
  ASSERT_GT(seized, 2 * M_PI);
  p.set_axis_faults(0, {.jam = true});
  test::run(p, 0.5, test::torque(0.6));
  EXPECT_NEAR(p.feedback(0).load_position, seized, 0.01);
  p.set_axis_faults(0, {});
  test::run(p, 0.2, test::torque(0.6));
  EXPECT_GT(p.feedback(0).load_position, seized + 1.0);  // free again
}

}  // namespace
}  // namespace vdrive::plant
