// Cyclic synchronous position (vdrive/drive/modes/cyclic_position_mode.hpp) fed with 1 ms bus
// set-points on each product's plant, and its product rules: the A6B command-jump alarm Err27.4
// and its 3722h bit 5 saturation (L16918-L17124), the DS1000A-EC clamp to 6080h (L2283-L2331),
// the DS5C1 ignoring 60B0h (L10025-L10039), halt, following error, a lost set-point.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/drive/control/control_test_bench.hpp"
#include "vdrive/drive/modes/cyclic_position_mode.hpp"

namespace vdrive::drive {
namespace {

using test::AxisBench;

constexpr std::uint16_t kEnabled = cw::switch_on | cw::enable_voltage | cw::quick_stop | cw::enable_operation;
constexpr Nanos kMs = 1'000'000;

void set_max_speed(AxisBench& b, std::uint32_t rpm) { b.set<std::uint32_t>(0x6080, 0, rpm); }

class CspProducts : public ::testing::TestWithParam<const char*> {};

// A 1 Hz sine of two revolutions (20000 user units; peak 126 user units per 1 ms cycle) written
// once per bus cycle. The demand lags the master by one cycle by design, so the actual position
// stays within one cycle's travel (126) plus a small loop error of the command.
TEST_P(CspProducts, FollowsASineFedEveryBusCycle) {
  for (const bool announce : {true, false}) {  // engine calls on_cycle(), or value-change detection
    AxisBench b(GetParam());
    set_max_speed(b, 3000);
    b.set<std::uint32_t>(0x6065, 0, 1000);  // following error window
    b.set<std::uint16_t>(0x6066, 0, 10);
    CyclicPositionMode csp(b.ctx());
    b.enable(csp);
    double commanded = 0.0, worst = 0.0;
    auto master = [&](Nanos t) {
      commanded = 20000.0 * std::sin(2.0 * std::numbers::pi * static_cast<double>(t) * 1e-9);
      b.set<std::int32_t>(0x607A, 0, static_cast<std::int32_t>(std::lround(commanded)));
    };
    b.run(csp, 2000 * kMs, kEnabled, master, [&] {
      if (b.now() > 500 * kMs) worst = std::max(worst, std::abs(commanded - b.position_user()));
      EXPECT_EQ(csp.status_bits() & sw::oms13, 0) << "following error at " << b.now();
    }, kMs, announce);
    EXPECT_LT(worst, 200.0) << GetParam() << (announce ? " on_cycle" : " value change");
    EXPECT_TRUE(csp.status_bits() & sw::oms12);  // drive follows the command value
    EXPECT_TRUE(csp.pending_alarm().empty());
  }
}

INSTANTIATE_TEST_SUITE_P(EachProduct, CspProducts, ::testing::Values("a6b", "ds5c1", "ds1000a"));

// Between two bus set-points the demand moves linearly over the cycle (one cycle of delay): no
// step for the loops even though the master steps every 1 ms.
TEST(CyclicPositionMode, DemandMovesLinearlyBetweenSetPoints) {
  AxisBench b("a6b");
  set_max_speed(b, 3000);
  CyclicPositionMode csp(b.ctx());
  b.enable(csp);
  b.set<std::int32_t>(0x607A, 0, 0);
  b.run(csp, 2 * kMs, kEnabled, [](Nanos) {});
  b.set<std::int32_t>(0x607A, 0, 400);
  csp.on_cycle(b.now());
  const Nanos start = b.now();
  const int steps = static_cast<int>(kMs / b.control_period());
  for (int i = 0; i < steps; ++i) {
    b.step(csp, kEnabled);
    const double expected = 400.0 * static_cast<double>(b.now() - b.control_period() - start) / kMs;
    EXPECT_NEAR(b.last_setpoint().position, expected, 1e-6) << i;
    EXPECT_NEAR(b.last_setpoint().velocity, 400.0 / 1e-3, 1e-6);  // feed-forward: 400 per ms
  }
  // The master keeps announcing cycles with 607Ah unchanged (without cycles the mode would
  // extrapolate a lost set-point for two cycles, LostSetPointsAreExtrapolatedForTwoCycles).
  b.run(csp, 3 * kMs, kEnabled, [](Nanos) {});
  EXPECT_DOUBLE_EQ(b.last_setpoint().position, 400.0);  // value-repeat: holds
}

// A6B: 60B0h is added to 607Ah, 60B1h/60B2h are feed-forwards (L15925-L17124). DS5C1: all three
// are accepted and ignored (L10025-L10039).
TEST(CyclicPositionMode, OffsetsOnlyWhereTheProductHonoursThem) {
  for (const bool honoured : {true, false}) {
    AxisBench b(honoured ? "a6b" : "ds5c1", [=](profile::ProductProfile& p) {
      test::pin_gains(p);
      p.drive.offsets_honoured = honoured;
    });
    set_max_speed(b, 3000);
    CyclicPositionMode csp(b.ctx());
    b.enable(csp);
    b.set<std::int32_t>(0x607A, 0, 100);
    b.set<std::int32_t>(0x60B0, 0, 50);
    b.set<std::int32_t>(0x60B1, 0, 7);
    b.set<std::int16_t>(0x60B2, 0, 30);
    b.run(csp, 5 * kMs, kEnabled, [](Nanos) {});
    EXPECT_DOUBLE_EQ(b.last_setpoint().position, honoured ? 150.0 : 100.0);
    EXPECT_DOUBLE_EQ(b.last_setpoint().velocity, honoured ? 7.0 : 0.0);
    EXPECT_DOUBLE_EQ(b.last_setpoint().torque, honoured ? 30.0 : 0.0);
  }
}

AxisBench::Tweak a6b_rules() {
  return [](profile::ProductProfile& p) {
    test::pin_gains(p);
    p.drive.csp_clamps_to_max_speed = false;
    p.drive.alarms.position_command_jump = "27.4";  // L16918-L17124, alarm table L32724
  };
}

// A6B: a per-cycle step beyond what 6080h allows is Err27.4. 6080h = 3000 r/min = 500000 user/s
// = 500 user units per 1 ms cycle.
TEST(CyclicPositionMode, A6bStepBeyondMaxMotorSpeedIsErr27_4) {
  AxisBench b("a6b", a6b_rules());
  ASSERT_NE(b.profile().find_alarm("27.4"), nullptr);
  set_max_speed(b, 3000);
  CyclicPositionMode csp(b.ctx());
  b.enable(csp);
  std::int32_t target = 0;
  auto master = [&](Nanos) { b.set<std::int32_t>(0x607A, 0, target); };
  target = 450;  // within the limit
  b.run(csp, 1 * kMs, kEnabled, master);
  EXPECT_TRUE(csp.pending_alarm().empty());
  target = 450 + 2000;  // 2000 in one cycle
  b.run(csp, 1 * kMs, kEnabled, master);
  EXPECT_EQ(csp.pending_alarm(), "27.4");
  // Cleared with the next enable (after the fault reset).
  b.enable(csp);
  EXPECT_TRUE(csp.pending_alarm().empty());
}

// The host takes one SYNC0 most of a cycle late and the next on time: two set-points 0.125 ms
// apart is the loop's jitter, not a faster bus, and no Err27.4 (a real A6B's interrupt is exact).
// A bus that really runs at 0.5 ms is adopted after a few cycles and judged on 0.5 ms.
TEST(CyclicPositionMode, A6bLateCycleInterruptIsNotAShorterCycle) {
  AxisBench b("a6b", a6b_rules());
  set_max_speed(b, 3000);  // 500 user units per 1 ms cycle
  CyclicPositionMode csp(b.ctx());
  b.enable(csp);
  std::int32_t target = 0;
  auto cycle = [&](Nanos until_next) {
    target += 450;
    b.set<std::int32_t>(0x607A, 0, target);
    csp.on_cycle(b.now());
    b.run(csp, until_next, kEnabled);
  };
  for (int c = 0; c < 10; ++c) cycle(kMs);
  const Nanos late = kMs - 2 * b.control_period();
  b.run(csp, late, kEnabled);
  cycle(kMs - late);
  for (int c = 0; c < 5; ++c) cycle(kMs);
  EXPECT_TRUE(csp.pending_alarm().empty());

  for (int c = 0; c < 10 && csp.pending_alarm().empty(); ++c) cycle(kMs / 2);
  EXPECT_EQ(csp.pending_alarm(), "27.4");  // 450 per 0.5 ms is beyond 3000 r/min
}

// A6B: the master must keep 607Ah on 6064h while disabled; a target far from the axis at enable
// is a jump (L16793-L16871).
TEST(CyclicPositionMode, A6bStaleTargetAtEnableIsAJump) {
  AxisBench b("a6b", a6b_rules());
  set_max_speed(b, 3000);
  CyclicPositionMode csp(b.ctx());
  b.set<std::int32_t>(0x607A, 0, 50000);
  b.enable(csp);
  b.run(csp, 1 * kMs, kEnabled, [](Nanos) {});
  EXPECT_EQ(csp.pending_alarm(), "27.4");
}

// A6B 3722h bit 5 = 1: the change per cycle saturates at the 6080h limit, no Err27.4 (L16918-L16996).
TEST(CyclicPositionMode, A6bSaturationBitLimitsTheStepInsteadOfAlarming) {
  AxisBench b("a6b", a6b_rules());
  set_max_speed(b, 3000);
  b.set<std::int16_t>(0x3722, 0, 1 << 5);
  CyclicPositionMode csp(b.ctx());
  b.enable(csp);
  b.set<std::int32_t>(0x607A, 0, 5000);
  b.run(csp, 1 * kMs, kEnabled, [](Nanos) {});
  EXPECT_TRUE(csp.pending_alarm().empty());
  EXPECT_TRUE(csp.clamped());
  // The demand at the end of that cycle (t = 1 ms, the master repeating 5000): one cycle's worth at
  // 3000 r/min. Later samples are further on: the demand goes on toward 5000 at 500 per cycle.
  b.step(csp, kEnabled, [](Nanos) {});
  EXPECT_NEAR(b.last_setpoint().position, 500.0, 1e-6);  // one cycle's worth at 3000 r/min
  EXPECT_TRUE(csp.pending_alarm().empty());
}

// DS1000A-EC: beyond 6080h the followed position is limited to what 6080h allows, and catches
// up at that speed (L2283-L2292, L2319-L2331); no alarm.
TEST(CyclicPositionMode, Ds1000aClampsToMaxMotorSpeedAndCatchesUp) {
  AxisBench b("ds1000a", [](profile::ProductProfile& p) {
    test::pin_gains(p);
    p.drive.csp_clamps_to_max_speed = true;
  });
  set_max_speed(b, 600);  // 600 r/min = 100000 user/s = 100 per cycle
  CyclicPositionMode csp(b.ctx());
  b.enable(csp);
  auto master = [&](Nanos) { b.set<std::int32_t>(0x607A, 0, 1000); };
  b.run(csp, 2 * kMs, kEnabled, master);
  EXPECT_LE(b.last_setpoint().position, 200.0 + 1e-6);
  EXPECT_TRUE(csp.clamped());
  b.run(csp, 12 * kMs, kEnabled, master);
  EXPECT_DOUBLE_EQ(b.last_setpoint().position, 1000.0);
  EXPECT_TRUE(csp.pending_alarm().empty());
}

// A set-point that does not arrive is bridged with the last increment per cycle (A6B command
// compensation, L16888-L16917), for at most two cycles; then the demand holds.
TEST(CyclicPositionMode, LostSetPointsAreExtrapolatedForTwoCycles) {
  AxisBench b("a6b");
  set_max_speed(b, 3000);
  CyclicPositionMode csp(b.ctx());
  b.enable(csp);
  std::int32_t target = 0;
  auto master = [&](Nanos) {
    target += 100;
    b.set<std::int32_t>(0x607A, 0, target);
  };
  b.run(csp, 5 * kMs, kEnabled, master);  // ramp of 100 per cycle; the demand one cycle behind
  const double at_loss = b.last_setpoint().position;
  b.run(csp, 2 * kMs, kEnabled);          // no set-points
  EXPECT_NEAR(b.last_setpoint().position, at_loss + 200.0, 1e-6);
  b.run(csp, 3 * kMs, kEnabled);
  EXPECT_NEAR(b.last_setpoint().position, target + 200.0, 1e-6);  // held after two cycles
}

// Halt (6040h bit 8): the demand stops on the 605Dh ramp (1 = 6084h) and bit 12 clears.
TEST(CyclicPositionMode, HaltDeceleratesOnTheProfileDecelerationAndStops) {
  AxisBench b("ds5c1");
  set_max_speed(b, 3000);
  b.set<std::int16_t>(0x605D, 0, 1);
  b.set<std::uint32_t>(0x6084, 0, 1'000'000);  // user/s^2
  CyclicPositionMode csp(b.ctx());
  b.enable(csp);
  std::int32_t target = 0;
  auto master = [&](Nanos) {
    target += 100;  // 100000 user/s
    b.set<std::int32_t>(0x607A, 0, target);
  };
  b.run(csp, 20 * kMs, kEnabled, master);
  const double at_halt = b.last_setpoint().position;
  const double v0 = b.last_setpoint().velocity;
  ASSERT_NEAR(v0, 100000.0, 1e-6);
  // Stopping distance v^2 / 2a = 1e10 / 2e6 = 5000 user units, in v / a = 100 ms.
  b.run(csp, 150 * kMs, kEnabled | cw::halt, master);
  EXPECT_DOUBLE_EQ(b.last_setpoint().velocity, 0.0);
  EXPECT_NEAR(b.last_setpoint().position - at_halt, 5000.0, 50.0);
  const double stopped = b.last_setpoint().position;
  b.run(csp, 10 * kMs, kEnabled | cw::halt, master);
  EXPECT_DOUBLE_EQ(b.last_setpoint().position, stopped);
  EXPECT_EQ(csp.status_bits() & sw::oms12, 0);
}

// Bit 13: |6062h - 6064h| beyond 6065h for longer than 6066h (A6B L14279-L14407, DS1000A-EC
// L1341-L1357). Samples made by hand: demand 500 ahead of the axis.
TEST(CyclicPositionMode, FollowingErrorBitAfterWindowAndTime) {
  AxisBench b("ds1000a");
  b.set<std::uint32_t>(0x6065, 0, 100);
  b.set<std::uint16_t>(0x6066, 0, 5);
  CyclicPositionMode csp(b.ctx());
  AxisSample s;
  s.dt_s = 125e-6;
  csp.activate(s);
  for (int i = 0; i <= 60; ++i) {
    s.time = i * 125'000;
    s.position_demand = 500.0;
    s.position = 0.0;
    csp.step(s, kEnabled);
    EXPECT_EQ((csp.status_bits() & sw::oms13) != 0, s.time >= 5 * kMs) << s.time;
  }
  s.position = 450.0;  // back inside the window
  csp.step(s, kEnabled);
  EXPECT_EQ(csp.status_bits() & sw::oms13, 0);
}

}  // namespace
}  // namespace vdrive::drive
