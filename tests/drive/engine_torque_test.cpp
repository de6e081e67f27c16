// Torque on the whole drive, from power-up, checked on the plant's motor torque: the profile
// torque mode ramps 6074h (and the torque the motor makes, 6077h) at the torque slope 6087h; the
// max torque 6072h caps it; the positive/negative torque limits 60E0h/60E1h cap each direction in
// the modes the product applies them to. Lines: A6B panasonic-minas-a6b-ethercat-spec.zh.txt,
// DS5C1 xinje-ds5c1-user-manual.zh.md, DS1000A-EC ds1000a-ec-manual.ja.txt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

// A heavier load (200 times the rotor) so that seconds of torque stay well below every speed limit
// (the DS1000A-EC caps tq at 500 r/min, L3315-L3318) and the torque is the only thing that acts.
EngineBench::Tweak heavy_load() {
  return [](profile::ProductProfile&, plant::PlantDescription& d) {
    d.axes[0].load_inertia_kgm2 = 200.0 * d.axes[0].motor.rotor_inertia_kgm2;
  };
}

// The torque the plant's motor makes, in 6077h's unit: 0.1 % of the motor's rated torque (the
// tweak above leaves the default plant's motor as it is).
double plant_torque(const EngineBench& b) {
  const double rated = drive::default_plant(b.profile()).axes.at(0).motor.rated_torque_nm;
  return b.feedback().torque_nm / rated * 1000.0;
}

class EngineTorque : public ::testing::TestWithParam<std::string> {
protected:
  void SetUp() override { bench = std::make_unique<EngineBench>(GetParam(), heavy_load()); }
  std::unique_ptr<EngineBench> bench;
};

// 6087h = 500 (50.0 %/s): 6071h = 10.0 % is reached in 200 ms, then -10.0 % in 400 ms more, 6074h
// and the motor's torque on the straight line of the slope (A6B L23993-L24003 and the figure
// L24034-L24046; DS5C1 L4331, 6087h L4266; DS1000A-EC 8.9.4 L3297-L3299 with 8.9.5 L3307-L3309).
TEST_P(EngineTorque, TorqueSlopeRampsTheDemandAndTheMotorTorque) {
  EngineBench& b = *bench;
  constexpr double kSlope = 500.0;  // 0.1 %/s
  b.set(0x6087, 0, std::llround(kSlope));
  ASSERT_TRUE(b.enable(mode::tq)) << b.diag();
  double worst_demand = 0.0, worst_motor = 0.0, peak_rpm = 0.0;
  Nanos t0 = b.now();
  double from = 0.0, to = 100.0;
  auto watch = [&](Nanos now) {
    const double ms = static_cast<double>(now - t0) / 1e6;
    const double expected = from + std::clamp(to - from, -kSlope * ms / 1000.0, kSlope * ms / 1000.0);
    worst_demand = std::max(worst_demand, std::abs(static_cast<double>(b.get(0x6074)) - expected));
    worst_motor = std::max(worst_motor, std::abs(plant_torque(b) - static_cast<double>(b.get(0x6074))));
    peak_rpm = std::max(peak_rpm, std::abs(b.motor_rpm()));
  };
  b.set(0x6071, 0, 100);
  b.run(300 * kMs, watch);
  EXPECT_NEAR(static_cast<double>(b.get(0x6074)), 100.0, 0.5) << b.diag();
  EXPECT_NEAR(static_cast<double>(b.get(0x6077)), 100.0, 2.0) << "6077h: the torque the motor makes";
  t0 = b.now();
  from = 100.0;
  to = -100.0;
  b.set(0x6071, 0, -100);
  b.run(500 * kMs, watch);
  EXPECT_NEAR(static_cast<double>(b.get(0x6074)), -100.0, 0.5) << b.diag();
  // The master samples once per 1 ms cycle while the slope moves 0.5 per ms, and 6074h is rounded:
  // the demand sits within one cycle's ramp (0.5) plus rounding (0.5) of the line.
  EXPECT_LE(worst_demand, 1.0) << "6074h follows 6087h";
  // The motor follows the demand through the torque filter and current loop (about 1 ms, 0.5 of
  // ramp) and the rounding of 6074h: within 2.0 (0.2 % of rated).
  EXPECT_LE(worst_motor, 2.0) << "the motor's torque follows 6074h";
  EXPECT_LT(peak_rpm, 300.0) << "far from every speed limit (the bench's heavy load)";
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
}

// 6072h caps the target torque: 6071h = +-20.0 % with 6072h = 5.0 % makes +-5.0 % (A6B
// L24020-L24022; DS5C1 L4337; DS1000A-EC 7.5.2 L1535-L1537 in the torque-control settings 7.5).
TEST_P(EngineTorque, MaxTorqueCapsTheTargetTorque) {
  EngineBench& b = *bench;
  b.set(0x6087, 0, 100000);  // 10000 %/s: the ramp is done within a millisecond
  b.set(0x6072, 0, 50);
  ASSERT_TRUE(b.enable(mode::tq)) << b.diag();
  for (const int target : {200, -200}) {
    b.set(0x6071, 0, target);
    b.run(50 * kMs);
    const double capped = target > 0 ? 50.0 : -50.0;
    EXPECT_NEAR(static_cast<double>(b.get(0x6074)), capped, 0.5) << target << " " << b.diag();
    EXPECT_NEAR(plant_torque(b), capped, 1.0) << "the motor makes the capped torque";
  }
}

// A6B: 60E0h/60E1h limit the positive and the negative torque when 3521h = 5 (L12910-L12926),
// in every mode including tq (Op-mode "ALL"): 6071h = +20.0 % makes 4.0 %, -20.0 % makes -7.0 %.
TEST(EngineTorqueLimit, A6bPositiveAndNegativeLimitsInProfileTorque) {
  EngineBench b("a6b", heavy_load());
  b.set(0x3521, 0, 5);
  b.set(0x60E0, 0, 40);
  b.set(0x60E1, 0, 70);
  b.set(0x6087, 0, 100000);
  ASSERT_TRUE(b.enable(mode::tq)) << b.diag();
  b.set(0x6071, 0, 200);
  b.run(50 * kMs);
  EXPECT_NEAR(plant_torque(b), 40.0, 1.0) << "positive torque capped by 60E0h " << b.diag();
  b.set(0x6071, 0, -200);
  b.run(50 * kMs);
  EXPECT_NEAR(plant_torque(b), -70.0, 1.0) << "negative torque capped by 60E1h, not by 60E0h " << b.diag();
}

// A6B: with 3521h other than 5 the drive does not use 60E0h/60E1h (L12916, L12926).
TEST(EngineTorqueLimit, A6bIgnores60E0hWithoutSelection5) {
  EngineBench b("a6b", heavy_load());
  b.set(0x3521, 0, 0);
  b.set(0x60E0, 0, 40);
  b.set(0x60E1, 0, 70);
  b.set(0x6087, 0, 100000);
  ASSERT_TRUE(b.enable(mode::tq)) << b.diag();
  for (const int target : {200, -200}) {
    b.set(0x6071, 0, target);
    b.run(50 * kMs);
    EXPECT_NEAR(plant_torque(b), target, 1.0) << b.diag();
  }
}

// In profile velocity, a step of 60FFh with a steep ramp asks the velocity loop for more torque
// than the limits allow: accelerating (positive torque) the motor makes at most 60E0h, braking
// (negative torque) at most 60E1h. A6B with 3521h = 5 (L12910-L12926); DS5C1 60E0h/60E1h apply in
// PP/PV/HM (L10147-L10158); DS1000A-EC: CW/CCW torque limits in the position and velocity modes
// (10.3, L3848, L3870-L3874).
TEST_P(EngineTorque, PositiveAndNegativeLimitsCapTheVelocityLoop) {
  EngineBench& b = *bench;
  if (b.has(0x3521)) b.set(0x3521, 0, 5);
  b.set(0x60E0, 0, 40);
  b.set(0x60E1, 0, 70);
  b.set(0x6083, 0, std::llround(10000 * b.per_rev()));
  b.set(0x6084, 0, std::llround(10000 * b.per_rev()));
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  double highest = -1e9, lowest = 1e9;
  auto watch = [&](Nanos) {
    highest = std::max(highest, plant_torque(b));
    lowest = std::min(lowest, plant_torque(b));
  };
  b.set(0x60FF, 0, std::llround(b.user_speed(50)));
  b.run(3000 * kMs, watch);
  EXPECT_NEAR(b.motor_rpm(), 50.0, 1.0) << "reaches the speed, slowly " << b.diag();
  // The limit clamps the velocity loop's output; the current loop makes it within 1.0 (0.1 %).
  EXPECT_NEAR(highest, 40.0, 1.0) << "accelerating: 60E0h";
  b.set(0x60FF, 0, 0);
  b.run(3000 * kMs, watch);
  EXPECT_NEAR(lowest, -70.0, 1.0) << "braking: 60E1h";
  EXPECT_LT(std::abs(b.motor_rpm()), 2.0) << b.diag();
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
}

INSTANTIATE_TEST_SUITE_P(Products, EngineTorque, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::drive::test
