// The DS1000A-EC's closed-loop stepper (vdrive/drive/control/stepper_loop.hpp): the loop mode
// 210Dh (L4040-L4050: 0 always closed, 1 open at or below 210Eh, 2 always open), the open-loop
// current 2112h (L4081), and open-loop micro-stepping on the real plant.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/drive/control/control_test_bench.hpp"
#include "vdrive/drive/control/stepper_loop.hpp"

namespace vdrive::drive {
namespace {

using test::AxisBench;

constexpr double kRpm = 2.0 * std::numbers::pi / 60.0;

// The profile's StepperSpec with fixed values (index 0: the fallback is the value).
AxisBench::Tweak stepper(double loop_mode, double switch_rpm, double current) {
  return [=](profile::ProductProfile& p) {
    p.drive.stepper = true;
    p.drive.stepper_loop.loop_mode = {0, 0, 1.0, loop_mode};
    p.drive.stepper_loop.switch_speed_rpm = {0, 0, 1.0, switch_rpm};
    p.drive.stepper_loop.run_current = {0, 0, 1.0, current};
  };
}

TEST(StepperLoop, AlwaysOpenImposesTheSetPointAngleAtTheOpenLoopCurrent) {
  AxisBench b("ds1000a", stepper(2, 0, 0.5));
  StepperLoop loop(b.ctx(), b.motor());
  plant::AxisFeedback fb;
  loop.reset(fb);
  EXPECT_EQ(loop.loop_mode(), StepperLoop::LoopMode::Open);
  const plant::AxisCommand cmd = loop.step({Setpoint::Kind::Position, 1.25, 3.0, 0.0, 0.0}, fb, 125e-6);
  EXPECT_TRUE(cmd.stepper_open_loop);
  EXPECT_DOUBLE_EQ(cmd.stepper_angle_rad, 1.25);
  EXPECT_DOUBLE_EQ(cmd.stepper_current, 0.5);
  EXPECT_TRUE(loop.open_loop());
}

TEST(StepperLoop, AlwaysClosedDrivesATorqueDemand) {
  AxisBench b("ds1000a", stepper(0, 0, 0.5));
  StepperLoop loop(b.ctx(), b.motor());
  plant::AxisFeedback fb;
  loop.reset(fb);
  const plant::AxisCommand cmd = loop.step({Setpoint::Kind::Position, 0.1, 0.0, 0.0, 0.0}, fb, 125e-6);
  EXPECT_FALSE(cmd.stepper_open_loop);
  EXPECT_GT(cmd.torque_nm, 0.0);
}

// 210Dh = 1: open loop at or below the switch speed 210Eh, closed loop above it (L4040-L4058).
TEST(StepperLoop, OpenBelowTheSwitchSpeedClosedAbove) {
  AxisBench b("ds1000a", stepper(1, 300, 0.8));
  StepperLoop loop(b.ctx(), b.motor());
  plant::AxisFeedback fb;
  loop.reset(fb);
  const MotorSetpoint sp{Setpoint::Kind::Position, 0.0, 0.0, 0.0, 0.0};
  EXPECT_TRUE(loop.step(sp, fb, 125e-6).stepper_open_loop);
  fb.motor_velocity_rad_s = 500 * kRpm;
  EXPECT_FALSE(loop.step(sp, fb, 125e-6).stepper_open_loop);
  fb.motor_velocity_rad_s = 200 * kRpm;
  EXPECT_TRUE(loop.step(sp, fb, 125e-6).stepper_open_loop);
}

// 210Dh = 1 with 210Eh = 0: open loop once the motor has stood still for 2113h (100 ms by default,
// L4087-L4092, L4820).
TEST(StepperLoop, ZeroSwitchSpeedOpensAfterStandstill) {
  AxisBench b("ds1000a", stepper(1, 0, 0.8));
  StepperLoop loop(b.ctx(), b.motor());
  plant::AxisFeedback fb;
  loop.reset(fb);
  const MotorSetpoint sp{Setpoint::Kind::Position, 0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < 700; ++i) EXPECT_FALSE(loop.step(sp, fb, 125e-6).stepper_open_loop) << i;  // 87.5 ms
  for (int i = 0; i < 200; ++i) loop.step(sp, fb, 125e-6);
  EXPECT_TRUE(loop.open_loop());
  fb.motor_velocity_rad_s = 100 * kRpm;  // moving again: closed
  EXPECT_FALSE(loop.step(sp, fb, 125e-6).stepper_open_loop);
}

// The loop mode concerns positioning (位置決め時モード, L4040): velocity and torque set-points run closed.
TEST(StepperLoop, VelocityAndTorqueSetPointsRunClosedEvenWhenOpenIsSelected) {
  AxisBench b("ds1000a", stepper(2, 0, 0.8));
  StepperLoop loop(b.ctx(), b.motor());
  plant::AxisFeedback fb;
  loop.reset(fb);
  EXPECT_FALSE(loop.step({Setpoint::Kind::Velocity, 0.0, 10.0, 0.0, 0.0}, fb, 125e-6).stepper_open_loop);
  EXPECT_FALSE(loop.step({Setpoint::Kind::Torque, 0.0, 0.0, 0.05, 0.0}, fb, 125e-6).stepper_open_loop);
}

// Open-loop micro-stepping on the plant: a smooth move of two revolutions in 0.5 s (peak 240 r/min)
// loses no step, and the rotor stays within a quarter electrical cycle (2 pi / 50 / 4) of the command.
TEST(StepperLoop, OpenLoopMicroSteppingFollowsASmoothMoveWithoutLosingSteps) {
  AxisBench b("ds1000a", stepper(2, 0, 1.0));
  b.loop().reset(b.feedback());
  const double dt = static_cast<double>(b.control_period()) * 1e-9;
  const double distance = 4.0 * std::numbers::pi, duration = 0.5;
  double worst = 0.0;
  Nanos now = 0;
  for (int i = 0; now < 800'000'000; ++i) {
    const double t = std::min(static_cast<double>(now) * 1e-9, duration);
    // Cosine-shaped move: smooth start and stop.
    const double angle = 0.5 * distance * (1.0 - std::cos(std::numbers::pi * t / duration));
    b.plant().command(0, b.loop().step({Setpoint::Kind::Position, angle, 0.0, 0.0, 0.0}, b.feedback(), dt));
    now += b.control_period();
    b.plant().advance_to(now);
    worst = std::max(worst, std::abs(b.feedback().motor_angle_rad - angle));
    EXPECT_EQ(b.feedback().lost_steps, 0) << "t=" << t;
    if (b.feedback().lost_steps != 0) break;
  }
  EXPECT_LT(worst, 2.0 * std::numbers::pi / 50.0 / 4.0);
  EXPECT_NEAR(b.feedback().motor_angle_rad, distance, 2.0 * std::numbers::pi / 50.0 / 4.0);
}

}  // namespace
}  // namespace vdrive::drive
