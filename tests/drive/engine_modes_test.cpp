// Each product, each mode of its 6502h, from power-up: enable through the power state machine,
// command a motion as a master would, and check what the motor (the plant) did.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

bool has_mode(const profile::ProductProfile& p, std::int8_t m) {
  return std::find(p.modes.modes.begin(), p.modes.modes.end(), m) != p.modes.modes.end();
}

// Skips the test (returning from it) when the product does not list mode `m` in 6502h.
#define REQUIRE_MODE(m) \
  if (!has_mode(bench->profile(), (m))) GTEST_SKIP() << GetParam() << " has no mode " << int(m)

class EngineModes : public ::testing::TestWithParam<std::string> {
protected:
  void SetUp() override { bench = std::make_unique<EngineBench>(GetParam()); }


  // The profile parameters a master sets before a profile move: `rpm` speed, 20 rev/s^2 ramps.
  void profile_parameters(double rpm) {
    EngineBench& b = *bench;
    const double acc = 20.0 * b.per_rev();
    b.set(0x6081, 0, std::llround(b.user_speed(rpm)));
    b.set(0x6083, 0, std::llround(acc));
    b.set(0x6084, 0, std::llround(acc));
    if (b.has(0x6085)) b.set(0x6085, 0, std::llround(4 * acc));
    if (b.has(0x607F)) b.set(0x607F, 0, std::llround(b.user_speed(3000)));
  }

  std::unique_ptr<EngineBench> bench;
};

TEST_P(EngineModes, PowerUpIsSwitchOnDisabledWithRemoteInOp) {
  EngineBench& b = *bench;
  b.run(10 * kMs);
  EXPECT_EQ(b.engine().state(), PdsState::SwitchOnDisabled);
  EXPECT_EQ(b.status() & 0x004F, 0x0040) << b.diag();
  EXPECT_NE(b.status() & (1u << 9), 0) << "remote: ESM >= PreOp";
  EXPECT_EQ(b.get(0x603F), 0);
}

TEST_P(EngineModes, EnableSequenceReachesOperationEnabledAndHolds) {
  EngineBench& b = *bench;
  const std::int8_t m = has_mode(b.profile(), mode::csp) ? mode::csp : mode::pp;
  ASSERT_TRUE(b.enable(m)) << b.diag();
  EXPECT_EQ(b.status() & 0x006F, 0x0027) << b.diag();
  const double revs = b.motor_revs();
  b.run(200 * kMs);
  EXPECT_NEAR(b.motor_revs(), revs, 0.01) << "an enabled axis with no new set-point holds";
  EXPECT_TRUE(b.emergencies.empty());
}

TEST_P(EngineModes, ProfilePositionMovesTenRevolutionsIntoTheWindow) {
  REQUIRE_MODE(mode::pp);
  EngineBench& b = *bench;
  profile_parameters(600);
  // The position window a master sets for its machine: 0.001 rev. The factory value (A6B: 10
  // increments of a 23-bit encoder) is finer than the stick-slip of the plant's static friction.
  b.set(0x6067, 0, std::llround(b.per_rev() / 1000.0));
  ASSERT_TRUE(b.enable(mode::pp)) << b.diag();
  const std::int32_t start = b.position();
  const double start_revs = b.motor_revs();
  const auto target = static_cast<std::int32_t>(start + std::llround(10 * b.per_rev()));
  b.set(0x607A, 0, target);
  b.command(kCwEnable | kCwNewSetPoint, 5 * kMs);
  EXPECT_NE(b.status() & (1u << 12), 0) << "set-point acknowledged";
  b.command(kCwEnable, 1 * kMs);
  ASSERT_TRUE(b.run_until([&] { return (b.status() & (1u << 10)) != 0; }, 5'000 * kMs))
      << b.diag() << " 6064h-607Ah=" << b.position() - target << " 6067h=" << b.get(0x6067)
      << " 6062h-607Ah=" << b.get(0x6062) - target;
  const std::int64_t window = std::max<std::int64_t>(b.get(0x6067), 1);
  EXPECT_LE(std::llabs(static_cast<long long>(b.position()) - target), window);
  EXPECT_NEAR(b.motor_revs() - start_revs, 10.0, 0.01);
  b.run(200 * kMs);
  EXPECT_LE(std::llabs(static_cast<long long>(b.position()) - target), window) << "holds at the target";
}

TEST_P(EngineModes, ProfileVelocityHoldsItsSpeed) {
  REQUIRE_MODE(mode::pv);
  EngineBench& b = *bench;
  profile_parameters(600);
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.set(0x60FF, 0, std::llround(b.user_speed(300)));
  b.run(1000 * kMs);
  EXPECT_NEAR(b.motor_rpm(), 300.0, 6.0) << b.diag();
  double lo = 1e9, hi = -1e9;
  b.run(200 * kMs, [&](Nanos) {
    lo = std::min(lo, b.motor_rpm());
    hi = std::max(hi, b.motor_rpm());
  });
  EXPECT_NEAR(lo, 300.0, 6.0);
  EXPECT_NEAR(hi, 300.0, 6.0);
  EXPECT_NEAR(static_cast<double>(b.velocity()), b.user_speed(300), b.user_speed(6));
}

TEST_P(EngineModes, ProfileTorqueAcceleratesWithTheCommandedTorque) {
  REQUIRE_MODE(mode::tq);
  EngineBench& b = *bench;
  if (b.has(0x6087)) b.set(0x6087, 0, 100000);  // 10000 %/s: the ramp is done in 1 ms
  ASSERT_TRUE(b.enable(mode::tq)) << b.diag();
  b.set(0x6071, 0, 100);  // 10.0 % of rated torque
  const double w0 = b.feedback().motor_velocity_rad_s;
  b.run(5 * kMs);
  EXPECT_NEAR(static_cast<double>(b.get(0x6077)), 100.0, 15.0) << "6077h reports the torque it makes " << b.diag();
  b.run(10 * kMs);
  EXPECT_GT(b.feedback().motor_velocity_rad_s, w0 + 0.1) << "positive torque accelerates in the positive direction " << b.diag();
}

TEST_P(EngineModes, CyclicPositionFollowsARampedMove) {
  REQUIRE_MODE(mode::csp);
  EngineBench& b = *bench;
  ASSERT_TRUE(b.enable(mode::csp)) << b.diag();
  const double start = b.position();
  const double start_revs = b.motor_revs();
  // 2 revolutions in 1 s with a smooth (cosine) speed profile.
  const double distance = 2.0 * b.per_rev();
  const Nanos t0 = b.now();
  double worst = 0.0;
  b.run(1200 * kMs, [&](Nanos now) {
    const double u = std::clamp(static_cast<double>(now - t0) / 1e9, 0.0, 1.0);
    b.set(0x607A, 0, std::llround(start + distance * (1.0 - std::cos(std::numbers::pi * u)) / 2.0));
    worst = std::max(worst, std::abs(static_cast<double>(b.get(0x60F4))));
  });
  b.run(300 * kMs, [&](Nanos) { b.set(0x607A, 0, std::llround(start + distance)); });
  EXPECT_NEAR(b.motor_revs() - start_revs, 2.0, 0.01);
  EXPECT_LE(worst, static_cast<double>(b.get(0x6065))) << "60F4h stays inside the following error window 6065h";
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
}

TEST_P(EngineModes, CyclicVelocityHoldsSpeed) {
  REQUIRE_MODE(mode::csv);
  EngineBench& b = *bench;
  ASSERT_TRUE(b.enable(mode::csv)) << b.diag();
  const auto target = std::llround(b.user_speed(200));
  b.run(800 * kMs, [&](Nanos) { b.set(0x60FF, 0, target); });
  double lo = 1e9, hi = -1e9;
  b.run(200 * kMs, [&](Nanos) {
    b.set(0x60FF, 0, target);
    lo = std::min(lo, b.motor_rpm());
    hi = std::max(hi, b.motor_rpm());
  });
  EXPECT_NEAR(lo, 200.0, 4.0) << b.diag();
  EXPECT_NEAR(hi, 200.0, 4.0);
}

TEST_P(EngineModes, CyclicTorqueMakesTheCommandedTorque) {
  REQUIRE_MODE(mode::cst);
  EngineBench& b = *bench;
  ASSERT_TRUE(b.enable(mode::cst)) << b.diag();
  const double w0 = b.feedback().motor_velocity_rad_s;
  b.run(5 * kMs, [&](Nanos) { b.set(0x6071, 0, -80); });
  EXPECT_NEAR(static_cast<double>(b.get(0x6077)), -80.0, 15.0) << b.diag();
  b.run(10 * kMs, [&](Nanos) { b.set(0x6071, 0, -80); });
  EXPECT_LT(b.feedback().motor_velocity_rad_s, w0 - 0.1) << "negative torque turns the motor backwards " << b.diag();
}

TEST_P(EngineModes, HomingOnTheCurrentPositionPresetsHomeOffset) {
  REQUIRE_MODE(mode::hm);
  EngineBench& b = *bench;
  b.set(0x6098, 0, 37);
  b.set(0x607C, 0, 12345);
  ASSERT_TRUE(b.enable(mode::hm)) << b.diag();
  b.command(kCwEnable | kCwNewSetPoint, 20 * kMs);
  EXPECT_EQ(b.status() & (1u << 12 | 1u << 13), 1u << 12) << b.diag();
  EXPECT_NEAR(b.position(), 12345, 2);
}

// DS1000A-EC ip: the master streams one 60C1h-01h record per 1 ms (mapped into the RxPDO) with
// 6040h bit 4 set; the drive interpolates linearly between them (L2262-L2270, L2363).
TEST_P(EngineModes, InterpolatedPositionFollowsTheRecords) {
  REQUIRE_MODE(mode::ip);
  EngineBench& b = *bench;
  MappedOutputs rx;  // what the firmware tells the drive at PreOp->SafeOp
  rx.add(0x60C1, 1);
  b.engine().outputs_mapped(rx);
  b.set(0x60C4, 6, 1);  // open the record buffer (closed at power-on, L2563-L2566)
  ASSERT_TRUE(b.enable(mode::ip)) << b.diag();
  const double start = b.position();
  const double start_revs = b.motor_revs();
  const double distance = 2.0 * b.per_rev();
  const Nanos t0 = b.now();
  b.set(0x6040, 0, kCwEnable | kCwNewSetPoint);
  bool bit12 = true;
  b.run(1200 * kMs, [&](Nanos now) {
    const double u = std::clamp(static_cast<double>(now - t0) / 1e9, 0.0, 1.0);
    b.set(0x60C1, 1, std::llround(start + distance * (1.0 - std::cos(std::numbers::pi * u)) / 2.0));
    if (now > t0 + 5 * kMs) bit12 = bit12 && (b.status() & (1u << 12)) != 0;
  });
  EXPECT_TRUE(bit12) << "6041h bit 12: interpolation active";
  b.run(300 * kMs, [&](Nanos) { b.set(0x60C1, 1, std::llround(start + distance)); });
  EXPECT_NEAR(b.motor_revs() - start_revs, 2.0, 0.01) << b.diag();
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
}

// Method 19 on the plant's own home switch (on above 3 rad of the load, direct drive): the drive
// searches in the positive direction, comes back slowly across the edge and presets there.
TEST(EngineHoming, Method19FindsThePlantsHomeSwitchEdge) {
  for (const char* id : {"a6b", "ds5c1", "ds1000a"}) {
    SCOPED_TRACE(id);
    constexpr double kEdge = 3.0;  // rad
    EngineBench b(id, [](profile::ProductProfile&, plant::PlantDescription& d) {
      d.axes[0].switches.home = plant::PositionWindow{kEdge, 1e6};
    });
    b.set(0x6098, 0, 19);
    b.set(0x6099, 1, std::llround(b.user_speed(60)));
    b.set(0x6099, 2, std::llround(b.user_speed(3)));
    b.set(0x609A, 0, std::llround(20 * b.per_rev()));
    b.set(0x607C, 0, 0);
    ASSERT_TRUE(b.enable(mode::hm)) << b.diag();
    b.command(kCwEnable | kCwNewSetPoint, 1 * kMs);
    ASSERT_TRUE(b.run_until([&] { return (b.status() & (1u << 12 | 1u << 13)) != 0; }, 20'000 * kMs,
                            [&](Nanos) { b.set(0x6040, 0, kCwEnable | kCwNewSetPoint); }))
        << b.diag();
    b.run(200 * kMs, [&](Nanos) { b.set(0x6040, 0, kCwEnable | kCwNewSetPoint); });
    EXPECT_EQ(b.status() & (1u << 10 | 1u << 12 | 1u << 13), 1u << 10 | 1u << 12) << "homing attained " << b.diag();
    // 6064h now reads 0 at the switch edge: the motor angle there is the position's origin.
    const double edge_user = static_cast<double>(b.position()) -
                             (b.feedback().motor_angle_rad - kEdge) / (2.0 * std::numbers::pi) * b.per_rev();
    EXPECT_NEAR(edge_user, 0.0, 0.002 * b.per_rev());
  }
}

INSTANTIATE_TEST_SUITE_P(Products, EngineModes, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::drive::test
