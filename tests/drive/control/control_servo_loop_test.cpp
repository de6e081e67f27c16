// The servo cascade (vdrive/drive/control/servo_loop.hpp) on each product's default motor and
// plant: position steps and sines are tracked, speed is held under load, the torque chain filters
// and limits, and the gains come from the vendor parameters the profile names.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tests/drive/control/control_test_bench.hpp"
#include "vdrive/drive/control/servo_loop.hpp"
#include "vdrive/drive/control/stepper_loop.hpp"

namespace vdrive::drive {
namespace {

using test::AxisBench;

// Runs the loop alone (no mode) for `duration` with a set-point computed from the time.
template <typename SetpointAt, typename Check>
void run_loop(AxisBench& b, double duration_s, SetpointAt at, Check check) {
  const double dt = static_cast<double>(b.control_period()) * 1e-9;
  const int steps = static_cast<int>(std::lround(duration_s / dt));
  Nanos now = b.plant().time();
  for (int i = 0; i < steps; ++i) {
    const double t = static_cast<double>(now) * 1e-9;
    const MotorSetpoint sp = at(t);
    b.plant().command(0, b.loop().step(sp, b.feedback(), dt));
    now += b.control_period();
    b.plant().advance_to(now);
    check(static_cast<double>(now) * 1e-9, sp);
  }
}

class ServoLoopProducts : public ::testing::TestWithParam<const char*> {};

// A position step of one motor revolution settles, with the product's own gains (whatever its
// profile names) and only a modest overshoot.
TEST_P(ServoLoopProducts, PositionStepSettlesWithTheProductsOwnGains) {
  AxisBench b(GetParam(), {}, /*pinned_gains=*/false);
  b.loop().reset(b.feedback());
  const double target = 2.0 * std::numbers::pi;
  double peak = 0.0;
  run_loop(
      b, 1.5, [&](double) { return MotorSetpoint{Setpoint::Kind::Position, target, 0.0, 0.0, 0.0}; },
      [&](double, const MotorSetpoint&) { peak = std::max(peak, b.feedback().motor_angle_rad); });
  EXPECT_NEAR(b.feedback().motor_angle_rad, target, 0.005 * target);
  EXPECT_LT(peak, 1.3 * target);
  EXPECT_NEAR(b.feedback().motor_velocity_rad_s, 0.0, 0.5);
}

// A 2 Hz sine of 3 rad amplitude (peak speed 38 rad/s, peak acceleration 474 rad/s^2). With full
// velocity feed-forward the error is the velocity loop's lag: about a_max / (2 pi f_v Kp) =
// 474 / (314 * 100) = 0.015 rad; the bound allows three times that.
TEST_P(ServoLoopProducts, PositionLoopTracksASine) {
  AxisBench b(GetParam());
  b.loop().reset(b.feedback());
  const double a = 3.0, w = 2.0 * std::numbers::pi * 2.0;
  double worst = 0.0;
  run_loop(
      b, 1.5,
      [&](double t) {
        return MotorSetpoint{Setpoint::Kind::Position, a * std::sin(w * t), a * w * std::cos(w * t), 0.0, 0.0};
      },
      [&](double t, const MotorSetpoint& sp) {
        if (t > 0.5) worst = std::max(worst, std::abs(sp.angle_rad - b.feedback().motor_angle_rad));
      });
  EXPECT_LT(worst, 0.05);
}

// Velocity control at 150 rad/s; a load of half the rated torque against the motion is added after
// 0.4 s. The integrator takes it up: 0.4 s later the speed is back within 1 %.
TEST_P(ServoLoopProducts, VelocityLoopHoldsSpeedUnderLoad) {
  AxisBench b(GetParam());
  b.loop().reset(b.feedback());
  const double speed = 150.0;
  auto command = [&](double) { return MotorSetpoint{Setpoint::Kind::Velocity, 0.0, speed, 0.0, 0.0}; };
  run_loop(b, 0.4, command, [](double, const MotorSetpoint&) {});
  EXPECT_NEAR(b.feedback().motor_velocity_rad_s, speed, 0.01 * speed);
  b.plant().set_external_load(0, -0.5 * b.motor().rated_torque_nm);
  run_loop(b, 0.4, command, [](double, const MotorSetpoint&) {});
  double worst = 0.0;
  run_loop(b, 0.1, command, [&](double, const MotorSetpoint&) {
    worst = std::max(worst, std::abs(b.feedback().motor_velocity_rad_s - speed));
  });
  EXPECT_LT(worst, 0.01 * speed);
  // The motor now delivers the load torque plus friction.
  EXPECT_GT(b.feedback().torque_nm, 0.45 * b.motor().rated_torque_nm);
}

INSTANTIATE_TEST_SUITE_P(EachProduct, ServoLoopProducts, ::testing::Values("a6b", "ds5c1", "ds1000a"));

TEST(ServoLoop, TorqueDemandPassesTheFilterAndTheLimit) {
  AxisBench b("a6b", [](profile::ProductProfile& p) {
    test::PinnedGains g;
    g.tf = 1e-3;  // 1 ms filter
    test::pin_gains(p, g);
  });
  ServoLoop loop(b.ctx(), b.motor());
  plant::AxisFeedback fb;
  loop.reset(fb);
  const double dt = 125e-6;
  // Filter: after one time constant (8 steps of 125 us) 1 - e^-1 of a 0.1 N m step.
  plant::AxisCommand cmd;
  for (int i = 0; i < 8; ++i) cmd = loop.step({Setpoint::Kind::Torque, 0.0, 0.0, 0.1, 0.0}, fb, dt);
  EXPECT_NEAR(cmd.torque_nm, 0.1 * (1.0 - std::exp(-1.0)), 1e-9);
  EXPECT_FALSE(loop.saturated());
  // Limit: 0.5 N m asked, 0.2 N m allowed.
  for (int i = 0; i < 200; ++i) cmd = loop.step({Setpoint::Kind::Torque, 0.0, 0.0, 0.5, 0.2}, fb, dt);
  EXPECT_DOUBLE_EQ(cmd.torque_nm, 0.2);
  EXPECT_TRUE(loop.saturated());
  // No limit given: the motor's peak torque.
  for (int i = 0; i < 200; ++i) cmd = loop.step({Setpoint::Kind::Torque, 0.0, 0.0, -100.0, 0.0}, fb, dt);
  EXPECT_DOUBLE_EQ(cmd.torque_nm, -b.motor().peak_torque_nm);
}

TEST(ServoLoop, ResetStartsFromTheTorqueTheAxisDelivers) {
  AxisBench b("ds5c1");
  ServoLoop loop(b.ctx(), b.motor());
  plant::AxisFeedback fb;
  fb.torque_nm = 0.3;
  loop.reset(fb);
  // Set-point on the axis, at rest: the first output continues from 0.3 N m, no step to 0.
  const plant::AxisCommand cmd = loop.step({Setpoint::Kind::Position, 0.0, 0.0, 0.0, 0.0}, fb, 125e-6);
  EXPECT_GT(cmd.torque_nm, 0.2);
}

// Gains are read from the vendor parameter the profile names: SI = raw * scale, the fallback when
// it reads 0, the engine default when the profile names nothing. 6081h stands in for a vendor
// parameter (any U32 object the product has).
TEST(ServoLoop, GainsComeFromTheNamedParameter) {
  AxisBench b("a6b", [](profile::ProductProfile& p) {
    test::pin_gains(p);
    p.drive.gains.position_gain = {0x6081, 0, 0.1, 7.0};   // like A6B Pr1.00, 0.1/s
    p.drive.gains.inertia_ratio = {0, 0, 1.0, 2.5};        // 250 %
    p.drive.gains.velocity_gain = {0, 0, 1.0, 0.0};        // unset
  });
  ServoLoop loop(b.ctx(), b.motor());
  b.set<std::uint32_t>(0x6081, 0, 480);
  loop.reset(b.feedback());
  EXPECT_DOUBLE_EQ(loop.gains().position_gain, 48.0);
  EXPECT_DOUBLE_EQ(loop.gains().velocity_bandwidth_hz, engine_default_gains::velocity_bandwidth_hz);
  // Kv = J_rotor (1 + ratio) 2 pi f_v (xinje-ds5c1 digest §9.4, P0-07 L8658).
  EXPECT_NEAR(loop.gains().velocity_gain,
              b.motor().rotor_inertia_kgm2 * 3.5 * 2.0 * std::numbers::pi * engine_default_gains::velocity_bandwidth_hz,
              1e-12);
  b.set<std::uint32_t>(0x6081, 0, 0);
  loop.reset(b.feedback());
  EXPECT_DOUBLE_EQ(loop.gains().position_gain, 7.0);
}

TEST(ControlLoopFactory, ServosGetTheCascadeTheSteppersGetTheStepperLoop) {
  AxisBench servo("a6b");
  EXPECT_NE(dynamic_cast<ServoLoop*>(&servo.loop()), nullptr);
  AxisBench stepper("ds1000a");
  EXPECT_NE(dynamic_cast<StepperLoop*>(&stepper.loop()), nullptr);
}

}  // namespace
}  // namespace vdrive::drive
