// Analytic checks of the mechanics: a = T/J, friction breakaway, gravity on a vertical axis,
// energy conservation. Expected values are computed here from the description, not by the plant.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant.hpp"
#include "tests/plant/plant_test_util.hpp"

namespace vdrive::plant {
namespace {

using test::rotary;
using test::run;
using test::torque;

TEST(PlantMotion, ConstantTorqueOnFreeInertiaGivesTorqueOverInertia) {
  const double jl = 3e-4, jr = 1e-4, t = 0.8;
  Plant p(rotary(jl, jr));
  run(p, 0.05, torque(t));  // past the current loop's settling
  const double w0 = p.feedback(0).motor_velocity_rad_s;
  run(p, 0.5, torque(t));
  const double a = (p.feedback(0).motor_velocity_rad_s - w0) / 0.5;
  EXPECT_NEAR(a, t / (jl + jr), 0.01 * t / (jl + jr));
  EXPECT_NEAR(p.feedback(0).torque_nm, t, 1e-6);
}

TEST(PlantMotion, GearboxReflectsTorqueAndRotorInertia) {
  PlantDescription d = rotary(0.05, 1e-4);
  d.axes[0].transmission.kind = TransmissionKind::gearbox;
  d.axes[0].transmission.ratio = 10.0;
  Plant p(d);
  const double t = 1.0, expected = t * 10.0 / (0.05 + 1e-4 * 100.0);  // load rad/s^2
  run(p, 0.05, torque(t));
  const double v0 = p.feedback(0).load_velocity;
  run(p, 0.5, torque(t));
  const double a = (p.feedback(0).load_velocity - v0) / 0.5;
  EXPECT_NEAR(a, expected, 0.01 * expected);
  EXPECT_NEAR(p.feedback(0).motor_angle_rad, 10.0 * p.feedback(0).load_position, 1e-9);
}

TEST(PlantMotion, FrictionBreaksAwayAtTheConfiguredTorque) {
  PlantDescription d = rotary(3e-4);
  d.axes[0].friction = {.coulomb = 0.15, .breakaway = 0.2, .stribeck_velocity = 0.5, .viscous = 0};
  {
    Plant p(d);
    run(p, 1.0, torque(0.98 * 0.2));
    EXPECT_LT(std::abs(p.feedback(0).load_position), 1e-6);
    EXPECT_LT(std::abs(p.feedback(0).load_velocity), 1e-6);
  }
  {
    Plant p(d);
    run(p, 0.2, torque(1.02 * 0.2));
    EXPECT_GT(p.feedback(0).load_velocity, 1.0);
  }
  {
    // Well above the Stribeck velocity only Coulomb friction is left: a = (T - Fc) / J.
    Plant p(d);
    run(p, 0.3, torque(0.5));
    const double v0 = p.feedback(0).load_velocity;
    ASSERT_GT(v0, 5 * 0.5);
    run(p, 0.2, torque(0.5));
    const double a = (p.feedback(0).load_velocity - v0) / 0.2;
    EXPECT_NEAR(a, (0.5 - 0.15) / 4e-4, 0.01 * (0.5 - 0.15) / 4e-4);
  }
  {
    // Negative direction: same breakaway.
    Plant p(d);
    run(p, 1.0, torque(-0.98 * 0.2));
    EXPECT_LT(std::abs(p.feedback(0).load_position), 1e-6);
    run(p, 0.2, torque(-1.02 * 0.2));
    EXPECT_LT(p.feedback(0).load_velocity, -1.0);
  }
}

TEST(PlantMotion, ViscousFrictionGivesTerminalVelocity) {
  PlantDescription d = rotary(3e-4);
  d.axes[0].friction.viscous = 0.01;  // N m s/rad
  Plant p(d);
  run(p, 2.0, torque(0.5));  // time constant J/b = 40 ms
  EXPECT_NEAR(p.feedback(0).load_velocity, 0.5 / 0.01, 0.005 * 50);
}

// A vertical ball-screw axis: 20 kg on a slider along z, 10 mm lead.
PlantDescription vertical_axis() {
  PlantDescription d;
  d.step_s = 250e-6;
  d.substeps = 4;
  d.bodies.push_back({.name = "carriage", .mass_kg = 20.0, .position_m = {0, 0, 0.5},
                      .inertia_kgm2 = {0.1, 0.1, 0.1}});
  JointSpec j;
  j.name = "z";
  j.type = JointType::slider;
  j.child = "carriage";
  j.axis = {0, 0, 1};
  j.lower_stop = -0.4;
  j.upper_stop = 0.4;
  d.joints.push_back(j);
  AxisSpec a;
  a.name = "z";
  a.joint = "z";
  a.motor = test::test_motor(1.4e-5);
  a.transmission.kind = TransmissionKind::ball_screw;
  a.transmission.lead_m = 0.01;
  a.brake = {.fitted = true, .holding_torque_nm = 1.0};
  a.encoder.counts_per_rev = 8388608;
  d.axes.push_back(a);
  return d;
}

TEST(PlantMotion, VerticalAxisHoldsAgainstGravityWithTheRightTorque) {
  const double hold = 20.0 * 9.81 * 0.01 / (2 * M_PI);  // m g lead / 2pi
  {
    // The current loop needs a few hundred microseconds to build the torque (the carriage sags a
    // little meanwhile); from then on the axis must not accelerate at all.
    Plant p(vertical_axis());
    run(p, 0.01, torque(hold));
    const double v0 = p.feedback(0).load_velocity;
    EXPECT_LT(std::abs(v0), 1e-3);
    run(p, 1.0, torque(hold));
    EXPECT_LT(std::abs(p.feedback(0).load_velocity - v0), 1e-7);
    EXPECT_NEAR(p.feedback(0).torque_nm, hold, 1e-9);
  }
  {
    Plant p(vertical_axis());
    run(p, 0.2, torque(0.95 * hold));
    EXPECT_LT(p.feedback(0).load_velocity, -1e-3);  // sags
  }
  {
    Plant p(vertical_axis());
    run(p, 0.2, torque(1.05 * hold));
    EXPECT_GT(p.feedback(0).load_velocity, 1e-3);  // lifts
  }
}

TEST(PlantMotion, HoldingBrakeHoldsTheLoadWithNoTorque) {
  Plant p(vertical_axis());
  AxisCommand c;
  c.brake_released = false;
  run(p, 1.0, c);
  EXPECT_LT(std::abs(p.feedback(0).load_position), 1e-6);
  c.brake_released = true;  // release: the carriage falls
  run(p, 0.1, c);
  EXPECT_LT(p.feedback(0).load_velocity, -0.01);
}

// A coil driven from outside the drive (a PLC output wired to it) overrides the drive's command
// until control goes back to the drive.
TEST(PlantMotion, BrakeDrivenFromOutsideOverridesTheDrivesCommand) {
  Plant p(vertical_axis());
  AxisCommand c;
  c.brake_released = false;
  p.set_brake_control(0, true);
  run(p, 0.1, c);
  EXPECT_LT(p.feedback(0).load_velocity, -0.01) << "released from outside: the carriage falls";
  EXPECT_FALSE(p.last_command(0).brake_released) << "what the drive commands is still its own";
  p.set_brake_control(0, std::nullopt);
  run(p, 0.5, c);
  EXPECT_NEAR(p.feedback(0).load_velocity, 0.0, 1e-4) << "the drive's brake holds again";
  c.brake_released = true;
  p.set_brake_control(0, false);
  const double at = p.feedback(0).load_position;
  run(p, 0.5, c);
  EXPECT_LT(std::abs(p.feedback(0).load_position - at), 1e-6) << "engaged from outside: held";
}

TEST(PlantMotion, ExternalInputsAreReadBackAndOredWithTheSensors) {
  PlantDescription d = vertical_axis();
  d.axes[0].switches.home = PositionWindow{0.1, 0.2};
  Plant p(d);
  p.set_external_input(0, input::home | input::probe1);
  EXPECT_EQ(p.external_input(0), input::home | input::probe1);
  run(p, 0.01, torque(0.0));
  EXPECT_EQ(p.feedback(0).inputs & (input::home | input::probe1), input::home | input::probe1);
  p.set_external_input(0, 0);
  run(p, 0.01, torque(0.0));
  EXPECT_EQ(p.feedback(0).inputs & (input::home | input::probe1), 0u);
}

TEST(PlantMotion, EndStopStopsTheLoadAndIsReported) {
  PlantDescription d = vertical_axis();
  d.axes[0].switches.positive_limit = 0.35;
  d.axes[0].switches.home = PositionWindow{0.1, 0.2};
  Plant p(d);
  run(p, 0.02, torque(1.0));
  EXPECT_EQ(p.feedback(0).faults & fault::end_stop, 0u);
  run(p, 2.0, torque(1.0));
  EXPECT_NEAR(p.feedback(0).load_position, 0.4, 2e-3);
  EXPECT_NE(p.feedback(0).faults & fault::end_stop, 0u);
  EXPECT_NE(p.feedback(0).inputs & input::positive_limit, 0u);
  EXPECT_EQ(p.feedback(0).inputs & input::home, 0u);
}

// Pendulum-like check: with no friction the world's energy stays within 1 % over 10 s.
TEST(PlantMotion, EnergyIsConservedWithoutFriction) {
  PlantDescription d;
  d.step_s = 1e-3;
  d.substeps = 4;
  d.bodies.push_back({.name = "arm", .mass_kg = 2.0, .position_m = {0.3, 0, 0},
                      .inertia_kgm2 = {1e-3, 0.06, 0.06}});
  JointSpec j;
  j.name = "pivot";
  j.child = "arm";
  j.axis = {0, -1, 0};
  d.joints.push_back(j);
  AxisSpec a;
  a.name = "pivot";
  a.joint = "pivot";
  a.motor = test::test_motor(1e-4);
  d.axes.push_back(a);
  Plant p(d);
  const double e0 = p.energy();
  const double swing = 2.0 * 9.81 * 0.3;  // energy released falling from horizontal to vertical
  double worst = 0;
  for (int i = 0; i < 10000; ++i) {
    p.step();
    worst = std::max(worst, std::abs(p.energy() - e0));
  }
  EXPECT_LT(worst, 0.01 * swing);
  EXPECT_GT(std::abs(p.feedback(0).load_velocity) + std::abs(p.feedback(0).load_position), 0.1);
}

TEST(PlantMotion, SameDescriptionAndCommandsGiveIdenticalResults) {
  auto go = [] {
    PlantDescription d = rotary(3e-4);
    d.axes[0].friction = {.coulomb = 0.05, .breakaway = 0.08, .stribeck_velocity = 0.1, .viscous = 1e-3};
    Plant p(d);
    for (int i = 0; i < 2000; ++i) {
      p.command(0, torque(0.3 * std::sin(i * 0.01)));
      p.step();
    }
    return p.feedback(0);
  };
  const AxisFeedback a = go(), b = go();
  EXPECT_EQ(a.motor_angle_rad, b.motor_angle_rad);
  EXPECT_EQ(a.encoder.counts, b.encoder.counts);
  EXPECT_EQ(a.load_velocity, b.load_velocity);
}

TEST(PlantMotion, AdvanceToRunsWholeStepsUpToTheCallersTime) {
  Plant p(rotary(3e-4));
  EXPECT_EQ(p.advance_to(1'000'000), 4u);  // 1 ms of 250 us steps
  EXPECT_EQ(p.time(), 1'000'000);
  EXPECT_EQ(p.advance_to(1'200'000), 0u);
  EXPECT_EQ(p.advance_to(1'250'000), 1u);
}

TEST(PlantMotion, LinearBeltAxisAcceleratesAtForceOverMassWithReflectedRotor) {
  // Horizontal belt axis: 4 kg carriage, 30 mm pulley behind a 3:1 reduction.
  PlantDescription d;
  d.step_s = 250e-6;
  d.substeps = 4;
  d.bodies.push_back({.name = "carriage", .mass_kg = 4.0, .position_m = {0, 0, 0}, .inertia_kgm2 = {0.01, 0.01, 0.01}});
  JointSpec j;
  j.name = "x";
  j.type = JointType::slider;
  j.child = "carriage";
  j.axis = {1, 0, 0};
  d.joints.push_back(j);
  AxisSpec a;
  a.name = "x";
  a.joint = "x";
  a.motor = test::test_motor(2e-5);
  a.transmission = {.kind = TransmissionKind::belt, .ratio = 3.0, .pulley_diameter_m = 0.03};
  d.axes.push_back(a);
  Plant p(d);
  const double r = 0.015 / 3.0, t = 0.5;  // m per motor rad
  const double expected = (t / r) / (4.0 + 2e-5 / (r * r));
  run(p, 0.01, torque(t));
  const double v0 = p.feedback(0).load_velocity;
  run(p, 0.2, torque(t));
  EXPECT_NEAR((p.feedback(0).load_velocity - v0) / 0.2, expected, 0.01 * expected);
  EXPECT_NEAR(p.feedback(0).motor_angle_rad * r, p.feedback(0).load_position, 1e-12);
}

TEST(PlantMotion, ExternalLoadProfileActsOnTheLoad) {
  PlantDescription d = rotary(3e-4);
  d.axes[0].load_profile = {{0.0, 0.0}, {0.1, 0.0}, {0.1, -0.4}, {1.0, -0.4}};
  Plant p(d);
  run(p, 0.1, torque(0.4));  // accelerates while the profile is 0
  const double v = p.feedback(0).load_velocity;
  EXPECT_GT(v, 1.0);
  run(p, 0.2, torque(0.4));  // now the load torque cancels the motor's
  EXPECT_NEAR(p.feedback(0).load_velocity, v, 0.01 * v);
}

}  // namespace
}  // namespace vdrive::plant
