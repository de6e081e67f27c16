// Touch probe on the whole drive, triggered by the plant: a probe-1 window in the plant's switches
// (on while the load is inside it), 60B8h started, the axis driven through it in pv. 60BAh/60BBh
// latch the position where the input changed, within one control step's travel; 60B9h shows the
// channel enabled and the values stored; the DS1000A-EC also stamps the edge's time in 60D1h/60D2h.
// Lines: A6B panasonic-minas-a6b-ethercat-spec.zh.txt, DS5C1 xinje-ds5c1-user-manual.zh.md,
// DS1000A-EC ds1000a-ec-manual.ja.txt.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kRising = 1.0 * kTwoPi, kFalling = 1.5 * kTwoPi;  // load rad = motor rad (direct drive)
constexpr double kSpeedRpm = 60.0;                                 // 1 rev/s through the window
constexpr std::uint64_t kSystemTimeBase = 5'000'000'000;           // DC system time at t = 0: past 2^32
constexpr std::uint16_t kEnable = 1u << 0, kRisingEdge = 1u << 4, kFallingEdge = 1u << 5;
constexpr std::uint16_t kEnabled = 1u << 0, kRisingStored = 1u << 1, kFallingStored = 1u << 2;

class EngineTouchProbe : public ::testing::TestWithParam<std::string> {
protected:
  void SetUp() override {
    bench = std::make_unique<EngineBench>(GetParam(), [](profile::ProductProfile&, plant::PlantDescription& d) {
      d.axes[0].switches.probe1 = plant::PositionWindow{kRising, kFalling};
    });
  }
  std::unique_ptr<EngineBench> bench;
};

// 60B8h = enable, first event, external input (trigger select 0: A6B EXT1 L25158-L25260, DS5C1
// EXT1 L4546-L4552, DS1000A-EC IN1 L3617-L3625), rising edge, and falling edge where the product
// takes both at once (the DS5C1 asks not to, L4566: its channel is armed for the rising edge).
TEST_P(EngineTouchProbe, LatchesThePositionWhereThePlantsProbeInputChanged) {
  EngineBench& b = *bench;
  const bool both = b.profile().touch_probe.both_edges_at_once;
  if (GetParam() == "ds5c1") b.set(0x253E, 0, 1);  // P5-62: TP1 on SI1, as the manual asks (L4541-L4544)
  b.set(0x6083, 0, std::llround(20 * b.per_rev()));
  b.set(0x6084, 0, std::llround(20 * b.per_rev()));
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.run(50 * kMs);

  // Where the edges are in user units, from the axis at rest.
  const double p0 = static_cast<double>(b.position()), a0 = b.feedback().motor_angle_rad;
  auto user_at = [&](double angle) { return p0 + (angle - a0) / kTwoPi * b.per_rev(); };
  const bool has_time_stamps = b.has(0x60D1);
  const std::int64_t stamp_before = has_time_stamps ? b.get(0x60D1) : 0;

  b.set(0x60B8, 0, kEnable | kRisingEdge | (both ? kFallingEdge : 0));
  b.run(5 * kMs);
  EXPECT_EQ(b.get(0x60B9) & 0x7, kEnabled) << "channel 1 enabled, nothing stored yet " << b.diag();

  // The edges' instants, interpolated between the bus cycles that saw the angle before and after.
  Nanos t_rise = -1, t_fall = -1, t_before = 0;
  double angle_before = a0;
  const auto crossed = [&](double edge, Nanos now, double angle) {
    return t_before + static_cast<Nanos>((edge - angle_before) / (angle - angle_before) * double(now - t_before));
  };
  b.set(0x60FF, 0, std::llround(b.user_speed(kSpeedRpm)));
  b.run(2500 * kMs, [&](Nanos now) {
    b.bus.system_time_ns = kSystemTimeBase + static_cast<std::uint64_t>(now);
    const double angle = b.feedback().motor_angle_rad;
    if (t_rise < 0 && angle >= kRising) t_rise = crossed(kRising, now, angle);
    if (t_fall < 0 && angle >= kFalling) t_fall = crossed(kFalling, now, angle);
    t_before = now;
    angle_before = angle;
  });
  ASSERT_GT(b.motor_revs(), 2.0) << "driven through the window " << b.diag();
  ASSERT_GE(t_rise, 0);

  // An edge happens within one control step; the drive latches where the axis was in that step.
  // 1 rev/s for one 125 us step, +1 for 60BAh's rounding to a whole unit.
  const double step_travel = b.per_rev() * (kSpeedRpm / 60.0) * 125e-6 + 1.0;
  const std::uint16_t status = static_cast<std::uint16_t>(b.get(0x60B9));
  EXPECT_EQ(status & kEnabled, kEnabled) << "bit 0 channel enabled (A6B L25403-L25459, DS5C1 L10041-L10128, "
                                            "DS1000A-EC L3673-L3717)";
  EXPECT_EQ(status & kRisingStored, kRisingStored) << "bit 1 rising edge value stored";
  EXPECT_NEAR(static_cast<double>(b.get(0x60BA)), user_at(kRising), step_travel)
      << "60BAh: the position at the rising edge (A6B L25484-L25514, DS1000A-EC L3719-L3723)";
  if (both) {
    EXPECT_EQ(status & kFallingStored, kFallingStored) << "bit 2 falling edge value stored";
    EXPECT_NEAR(static_cast<double>(b.get(0x60BB)), user_at(kFalling), step_travel) << "60BBh at the falling edge";
  } else {
    EXPECT_EQ(status & kFallingStored, 0) << "DS5C1: the falling edge was not armed (L4566)";
  }

  if (has_time_stamps) {
    // DS1000A-EC: 60D1h/60D2h in ns (L3793-L3803), the low 32 bits of the DC system time. The
    // bench gives the drive the system time once per 1 ms bus cycle, as the firmware reads it
    // from the ESC when it runs, and the drive catches up the cycle's eight control steps at once:
    // each step still stamps the DC time of its own instant, so the stamp lies within the control
    // step of the edge (125 us), not merely within its bus cycle.
    const std::int64_t stamp = b.get(0x60D1);
    const double step = static_cast<double>(b.engine().control_period());
    EXPECT_NE(stamp, stamp_before) << "60D1h changed with the latch";
    const auto expected = static_cast<std::uint32_t>(kSystemTimeBase + static_cast<std::uint64_t>(t_rise));
    EXPECT_NEAR(static_cast<double>(stamp), static_cast<double>(expected), step) << "time of the rising edge";
    const auto expected_fall = static_cast<std::uint32_t>(kSystemTimeBase + static_cast<std::uint64_t>(t_fall));
    EXPECT_NEAR(static_cast<double>(b.get(0x60D2)), static_cast<double>(expected_fall), step)
        << "60D2h: time of the falling edge";
  }
  EXPECT_EQ(b.get(0x603F), 0) << b.diag();
}

// First-event mode latches once per start (A6B L25638-L25646): driven back through the window the
// stored values stay those of the first passage until 60B8h bit 0 goes 0 -> 1 again.
TEST_P(EngineTouchProbe, FirstEventLatchesOncePerStart) {
  EngineBench& b = *bench;
  if (GetParam() == "ds5c1") b.set(0x253E, 0, 1);
  b.set(0x6083, 0, std::llround(20 * b.per_rev()));
  b.set(0x6084, 0, std::llround(20 * b.per_rev()));
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.set(0x60B8, 0, kEnable | kRisingEdge);
  b.set(0x60FF, 0, std::llround(b.user_speed(kSpeedRpm)));
  b.run(2500 * kMs);
  const std::int64_t first = b.get(0x60BA);
  ASSERT_NE(b.get(0x60B9) & kRisingStored, 0) << b.diag();
  b.set(0x60FF, 0, std::llround(b.user_speed(-kSpeedRpm)));  // back through the window: rising at 1.5 rev
  b.run(2500 * kMs);
  ASSERT_LT(b.motor_revs(), 1.0) << b.diag();
  EXPECT_EQ(b.get(0x60BA), first) << "no second latch in first-event mode";
  b.set(0x60B8, 0, 0);
  b.run(2 * kMs);
  b.set(0x60B8, 0, kEnable | kRisingEdge);
  b.set(0x60FF, 0, std::llround(b.user_speed(kSpeedRpm)));
  b.run(1500 * kMs);
  EXPECT_NEAR(static_cast<double>(b.get(0x60BA)), static_cast<double>(first),
              b.per_rev() * (kSpeedRpm / 60.0) * 125e-6 * 2 + 2.0)
      << "restarted: latched again at the same edge";
}

INSTANTIATE_TEST_SUITE_P(Products, EngineTouchProbe, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::drive::test
