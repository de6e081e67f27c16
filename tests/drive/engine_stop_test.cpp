// Quick stop and halt on the whole drive, checked on the plant's speed:
//  - Quick stop (6040h = 0002h from Operation enabled) enters Quick stop active at once and
//    decelerates by 6085h to standstill; 605Ah = 2 then goes on to Switch on disabled, 605Ah = 6
//    stays in Quick stop active until Enable operation (transition 16) resumes the mode.
//  - Halt (6040h bit 8) in pv decelerates by the ramp 605Dh names (1: 6084h, 2: 6085h) and stays
//    Operation enabled; bit 10 is 1 once the axis stands; releasing it resumes the target speed.
// Lines: A6B panasonic-minas-a6b-ethercat-spec.zh.txt, DS5C1 xinje-ds5c1-user-manual.zh.md,
// DS1000A-EC ds1000a-ec-manual.ja.txt (its 605Ah/605Dh appear in the object table only, with the
// CiA 402 codes: L4899, L4905; the state machine and commands L894-L984, L1078).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

constexpr std::uint16_t kCwQuickStop = 0x0002;
constexpr double kSpeedRpm = 600.0;  // 10 rev/s

// The motor speed (r/min) once per bus cycle while `run` lasts.
std::vector<double> speeds(EngineBench& b, Nanos duration, const std::function<void(Nanos)>& also = {}) {
  std::vector<double> v;
  b.run(duration, [&](Nanos now) {
    v.push_back(b.motor_rpm());
    if (also) also(now);
  });
  return v;
}

// The deceleration (rev/s^2) of a speed record between 75 % and 25 % of its first value: the
// straight part of a ramp, free of the velocity loop's lag at its start and end.
double deceleration(const std::vector<double>& rpm) {
  const double v0 = std::abs(rpm.front());
  int t75 = -1, t25 = -1;
  for (std::size_t i = 0; i < rpm.size(); ++i) {
    if (t75 < 0 && std::abs(rpm[i]) <= 0.75 * v0) t75 = static_cast<int>(i);
    if (t25 < 0 && std::abs(rpm[i]) <= 0.25 * v0) t25 = static_cast<int>(i);
  }
  if (t75 < 0 || t25 <= t75) return 0.0;
  return (std::abs(rpm[t75]) - std::abs(rpm[t25])) / 60.0 / ((t25 - t75) * 1e-3);
}

struct QuickStopCase {
  const char* product;
  std::int16_t code;   // 605Ah
  std::int8_t mode;
};
void PrintTo(const QuickStopCase& c, std::ostream* os) { *os << c.product << " 605Ah=" << c.code << " mode " << int(c.mode); }

class EngineQuickStop : public ::testing::TestWithParam<QuickStopCase> {};

// 605Ah = 2 / 6: decelerate by 6085h (A6B L27013/L27019 "pp, csp, ip, csv, pv"; DS5C1 L4420; DS1000A-EC
// 605Ah factory 2, L4899, and 6085h L4981), Quick stop active while decelerating (A6B L27094-L27096,
// DS5C1 L4422-L4426), standstill at the product's stop speed (A6B 30 r/min L27098, DS5C1 10 r/min
// L4428), then Switch on disabled (2) or Quick stop active (6) (A6B L27100, DS5C1 L4430).
TEST_P(EngineQuickStop, DeceleratesBy6085hToStandstill) {
  const QuickStopCase c = GetParam();
  EngineBench b(c.product);
  constexpr double kQuickStop = 40.0, kProfile = 10.0;  // rev/s^2: 6085h differs from 6084h
  b.set(0x605A, 0, c.code);
  b.set(0x6081, 0, std::llround(b.user_speed(kSpeedRpm)));
  b.set(0x6083, 0, std::llround(50 * b.per_rev()));
  b.set(0x6084, 0, std::llround(kProfile * b.per_rev()));
  b.set(0x6085, 0, std::llround(kQuickStop * b.per_rev()));
  b.set(0x607F, 0, std::llround(b.user_speed(3000)));
  // The DS5C1 and DS1000-EC ship without velocity feed-forward (P1-10 = 0, L8711; 2106h = 0,
  // L4804): in pp their position loop lags the demand by v / Kp (half a revolution on the DS5C1 at
  // 10 rev/s), and the motor's speed shows the loop's lag rather than the ramp. A master that
  // profiles moves sets it: 100 % here (the A6B's factory 3110h is 100 %), so the plant follows the
  // demand and the ramp is measured on the motor.
  if (c.mode == mode::pp) {
    const auto& ff = b.profile().drive.gains.velocity_feedforward;
    if (ff.index != 0) b.set(ff.index, ff.subindex, std::llround(1.0 / ff.scale));
  }
  ASSERT_TRUE(b.enable(c.mode)) << b.diag();
  if (c.mode == mode::pv) {
    b.set(0x60FF, 0, std::llround(b.user_speed(kSpeedRpm)));
  } else {
    b.set(0x607A, 0, b.position() + std::llround(100 * b.per_rev()));
    b.command(kCwEnable | kCwNewSetPoint, 3 * kMs);
    b.command(kCwEnable, 1 * kMs);
  }
  b.run(500 * kMs);
  ASSERT_NEAR(b.motor_rpm(), kSpeedRpm, 12.0) << b.diag();

  b.set(0x6040, 0, kCwQuickStop);
  b.run(1 * kMs);
  EXPECT_EQ(b.engine().state(), PdsState::QuickStopActive) << "at once (A6B L27094-L27096) " << b.diag();
  EXPECT_EQ(b.status() & 0x006F, 0x0007) << "6041h x00x 0111 Quick stop active (A6B L10023-L10039, "
                                            "DS1000A-EC L1078) "
                                         << b.diag();
  const double revs = b.motor_revs();
  const std::vector<double> rpm = speeds(b, 400 * kMs);
  // The slope between 75 % and 25 % of the speed: 3 % for the 1 ms sampling of a 125 ms stretch.
  EXPECT_NEAR(deceleration(rpm), kQuickStop, 0.03 * kQuickStop) << "6085h, not 6084h";
  // From 10 rev/s at 40 rev/s^2: 1.25 rev (the ramp starts from the demand, ~1 ms behind).
  EXPECT_NEAR(b.motor_revs() - revs, 1.25, 0.03) << "stopping distance of the 6085h ramp";
  EXPECT_LT(std::abs(b.motor_rpm()), 1.0) << "standstill " << b.diag();
  if (c.code == 2) {
    EXPECT_EQ(b.engine().state(), PdsState::SwitchOnDisabled) << "605Ah = 2: then Switch on disabled " << b.diag();
    EXPECT_EQ(b.status() & 0x004F, 0x0040);
  } else {
    EXPECT_EQ(b.engine().state(), PdsState::QuickStopActive) << "605Ah = 6: stays Quick stop active " << b.diag();
    // Transition 16 (A6B L9773 "Enable operation from Quick stop active, 605Ah = 5, 6, 7"; DS5C1
    // L5968-L5998 T16; DS1000A-EC diagram L938): the mode runs again.
    b.command(kCwEnable, 5 * kMs);
    EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
    if (c.mode == mode::pv) {
      b.run(800 * kMs);
      EXPECT_NEAR(b.motor_rpm(), kSpeedRpm, 12.0) << "pv resumes its target " << b.diag();
    }
  }
  EXPECT_EQ(b.get(0x603F), 0) << b.diag();
}

const QuickStopCase kQuickStopCases[] = {
    {"a6b", 2, mode::pv}, {"a6b", 6, mode::pv}, {"a6b", 2, mode::pp},
    {"ds5c1", 2, mode::pv}, {"ds5c1", 6, mode::pv}, {"ds5c1", 2, mode::pp},
    {"ds1000a", 2, mode::pv}, {"ds1000a", 6, mode::pv}, {"ds1000a", 2, mode::pp},
};
INSTANTIATE_TEST_SUITE_P(Products, EngineQuickStop, ::testing::ValuesIn(kQuickStopCases), [](const auto& info) {
  return std::string(info.param.product) + "_" + std::to_string(info.param.code) + "_" +
         (info.param.mode == mode::pv ? "pv" : "pp");
});

class EngineHalt : public ::testing::TestWithParam<std::string> {};

// pv halt: 605Dh = 1 decelerates by 6084h, 2 by 6085h, staying Operation enabled (A6B L27418-L27422,
// DS5C1 L4481 and L4491-L4493, DS1000A-EC halt L886 with 605Dh L4905); bit 10 is 0 while
// decelerating and 1 once stopped (A6B L21500-L21507, DS1000A-EC L3071-L3081); halt back to 0
// resumes 60FFh (A6B L9912-L9916, DS1000A-EC L886-L888; the DS5C1 manual does not say otherwise).
TEST_P(EngineHalt, HaltInPvStopsWith605DhAndResumes) {
  EngineBench b(GetParam());
  constexpr double kProfile = 30.0, kQuickStop = 60.0;  // rev/s^2
  b.set(0x6083, 0, std::llround(50 * b.per_rev()));
  b.set(0x6084, 0, std::llround(kProfile * b.per_rev()));
  b.set(0x6085, 0, std::llround(kQuickStop * b.per_rev()));
  b.set(0x607F, 0, std::llround(b.user_speed(3000)));
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.set(0x60FF, 0, std::llround(b.user_speed(kSpeedRpm)));
  for (const std::int16_t code : {1, 2}) {
    SCOPED_TRACE(code);
    b.set(0x605D, 0, code);
    b.run(600 * kMs);
    ASSERT_NEAR(b.motor_rpm(), kSpeedRpm, 12.0) << b.diag();
    b.set(0x6040, 0, kCwEnable | kCwHalt);
    b.run(1 * kMs);  // the statusword the master reads next is the drive's answer to the halt
    bool bit10_moving = false, left_oe = false;
    const std::vector<double> rpm = speeds(b, 500 * kMs, [&](Nanos) {
      if ((b.status() & sw::target_reached) && std::abs(b.motor_rpm()) > 60.0) bit10_moving = true;
      if (b.engine().state() != PdsState::OperationEnabled) left_oe = true;
    });
    const double expected = code == 1 ? kProfile : kQuickStop;
    EXPECT_NEAR(deceleration(rpm), expected, 0.03 * expected) << "605Dh = " << code;
    EXPECT_LT(std::abs(b.motor_rpm()), 1.0) << b.diag();
    EXPECT_FALSE(bit10_moving) << "bit 10 = 0 while decelerating";
    EXPECT_NE(b.status() & sw::target_reached, 0) << "bit 10 = 1: stopped " << b.diag();
    EXPECT_FALSE(left_oe) << "halt keeps Operation enabled";

    b.set(0x6040, 0, kCwEnable);
    b.run(600 * kMs);
    EXPECT_NEAR(b.motor_rpm(), kSpeedRpm, 12.0) << "released: back to 60FFh " << b.diag();
  }
  EXPECT_EQ(b.get(0x603F), 0) << b.diag();
}

INSTANTIATE_TEST_SUITE_P(Products, EngineHalt, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::drive::test
