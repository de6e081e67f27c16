// Motor electrical/thermal behaviour: current loop, speed limit, thermal network, stepper
// stiffness and lost steps. Expected values come from the closed-form solutions.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant.hpp"
#include "plant/thermal_network.hpp"
#include "tests/plant/plant_test_util.hpp"

namespace vdrive::plant {
namespace {

using test::rotary;
using test::run;
using test::torque;

TEST(Motor, CurrentLoopIsAFirstOrderLagOfTheConfiguredBandwidth) {
  PlantDescription d = rotary(1.0);  // big load: speed stays ~0
  Plant p(d);
  p.command(0, torque(1.0));
  p.step();  // 4 substeps of 62.5 us
  const double t = 250e-6, f = d.axes[0].motor.current_bandwidth_hz;
  EXPECT_NEAR(p.feedback(0).torque_nm, 1.0 * (1 - std::exp(-2 * M_PI * f * t)), 1e-9);
  EXPECT_NEAR(p.feedback(0).current_a, p.feedback(0).torque_nm / 0.5, 1e-12);
}

TEST(Motor, TorqueIsClampedToPeak) {
  Plant p(rotary(1.0));
  run(p, 0.01, torque(100.0));
  EXPECT_NEAR(p.feedback(0).torque_nm, 6.0, 1e-9);
}

TEST(Motor, SpeedIsLimitedByTheBackEmfTaper) {
  PlantDescription d = rotary(1e-4);
  d.axes[0].motor.max_speed_rad_s = 300.0;
  Plant p(d);
  run(p, 0.5, torque(2.0));
  EXPECT_GT(p.feedback(0).motor_velocity_rad_s, 300.0);
  EXPECT_LE(p.feedback(0).motor_velocity_rad_s, 330.0);
  EXPECT_EQ(p.feedback(0).faults & fault::overspeed, 0u);
}

TEST(ThermalNetworkTest, SteadyStateAndInitialSlopeMatchTheRcNetwork) {
  MotorParams m;
  m.ambient_c = 20;
  m.winding_capacity_j_per_k = 60;
  m.housing_capacity_j_per_k = 600;
  m.winding_to_housing_k_per_w = 1;
  m.housing_to_ambient_k_per_w = 3;
  {
    ThermalNetwork t(m, 0.1);
    t.step(10.0);
    // First step: the winding warms at P / C_w, the housing not yet noticeably.
    EXPECT_NEAR(t.winding_c() - 20, 10.0 / 60 * 0.1, 0.01 * 10.0 / 60 * 0.1);
    EXPECT_LT(t.housing_c() - 20, 1e-3);
  }
  ThermalNetwork t(m, 1.0);
  for (int i = 0; i < 40000; ++i) t.step(10.0);
  EXPECT_NEAR(t.winding_c(), 20 + 10.0 * (1 + 3), 1e-6);  // P (R_wh + R_ha)
  EXPECT_NEAR(t.housing_c(), 20 + 10.0 * 3, 1e-6);
  for (int i = 0; i < 40000; ++i) t.step(0.0);
  EXPECT_NEAR(t.winding_c(), 20, 1e-6);
}

TEST(Motor, WindingHeatsByCopperLossAndOverloadIsFlagged) {
  PlantDescription d = rotary(1.0);
  d.step_s = 1e-3;
  d.substeps = 1;
  MotorParams& m = d.axes[0].motor;
  m.winding_resistance_ohm = 2.0;
  m.winding_capacity_j_per_k = 5.0;
  m.housing_capacity_j_per_k = 100.0;
  m.winding_to_housing_k_per_w = 2.0;
  m.housing_to_ambient_k_per_w = 2.0;
  m.winding_limit_c = 100.0;
  d.axes[0].friction.breakaway = d.axes[0].friction.coulomb = 50.0;  // stalled
  Plant p(d);
  run(p, 0.1, torque(6.0));  // 12 A: 288 W
  const double slope = 12.0 * 12.0 * 2.0 / 5.0;  // K/s at the start
  EXPECT_NEAR(p.feedback(0).winding_c - m.ambient_c, slope * 0.1, 0.05 * slope * 0.1);
  EXPECT_EQ(p.feedback(0).faults & fault::overtemperature, 0u);
  run(p, 2.0, torque(6.0));
  EXPECT_GT(p.feedback(0).winding_c, 100.0);
  EXPECT_NE(p.feedback(0).faults & fault::overtemperature, 0u);
  p.clear_faults(0);
  EXPECT_EQ(p.feedback(0).faults, 0u);
}

// A 1.8 deg hybrid stepper (50 teeth) in open loop: holding 0.3 N m.
PlantDescription stepper_axis() {
  PlantDescription d;
  d.step_s = 250e-6;
  d.substeps = 4;
  AxisSpec a;
  a.name = "s";
  a.motor.kind = MotorKind::stepper;
  a.motor.rated_torque_nm = a.motor.peak_torque_nm = 0.3;
  a.motor.rated_current_a = 2.0;
  a.motor.torque_constant_nm_per_a = 0.15;
  a.motor.rotor_inertia_kgm2 = 3.8e-6;
  a.motor.max_speed_rad_s = 314;
  a.load_inertia_kgm2 = 1e-5;
  a.friction.viscous = 0.005;
  a.encoder.counts_per_rev = 16000;
  a.encoder.absolute = false;
  a.encoder.multiturn_bits = 0;
  d.axes.push_back(a);
  return d;
}

AxisCommand open_loop(double angle) {
  AxisCommand c;
  c.stepper_open_loop = true;
  c.stepper_angle_rad = angle;
  c.stepper_current = 1.0;
  return c;
}

TEST(Stepper, HoldsALoadBelowHoldingTorqueAtTheSineLawDeflection) {
  Plant p(stepper_axis());
  p.set_external_load(0, -0.25);
  run(p, 0.5, open_loop(0.0));
  // -T_h sin(50 theta) = 0.25 at rest.
  EXPECT_NEAR(p.feedback(0).motor_angle_rad, -std::asin(0.25 / 0.3) / 50, 1e-4);
  EXPECT_EQ(p.feedback(0).lost_steps, 0);
}

// Ramp the commanded angle to 8 rad/s and run; returns the plant afterwards.
Plant run_move(double load) {
  Plant p(stepper_axis());
  p.set_external_load(0, load);
  double angle = 0, speed = 0;
  for (int i = 0; i < 4000; ++i) {  // 1 s
    speed = std::min(8.0, speed + 40.0 * p.step_s());
    angle += speed * p.step_s();
    p.command(0, open_loop(angle));
    p.step();
  }
  return p;
}

TEST(Stepper, FollowsTheCommandWhenTheLoadIsWithinItsTorque) {
  Plant p = run_move(-0.15);
  EXPECT_EQ(p.feedback(0).lost_steps, 0);
  EXPECT_EQ(p.feedback(0).faults & fault::lost_steps, 0u);
  EXPECT_GT(p.feedback(0).motor_angle_rad, 5.0);
}

TEST(Stepper, LosesStepsWhenTheLoadExceedsTheAvailableTorque) {
  Plant p = run_move(-0.35);
  EXPECT_GT(p.feedback(0).lost_steps, 0);
  EXPECT_EQ(p.feedback(0).lost_steps % 4, 0);  // whole electrical cycles
  EXPECT_NE(p.feedback(0).faults & fault::lost_steps, 0u);
}

}  // namespace
}  // namespace vdrive::plant
