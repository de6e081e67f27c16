// Software position limits 607Dh on the whole drive, per product rule (profile drive.soft_limits),
// checked on the plant:
//  - A6B (after homing: the factory incremental mode, L13151): in pp/ip/csp only (L13145); a move
//    beyond the limit decelerates by the quick-stop ramp 6085h from where the limit is detected
//    (L13212-L13218); outside the range only motion back toward it, bit 11 = 1 until back inside
//    (L13161-L13167, bit 11 table L10131); Init -> PreOp makes them inactive until homed again
//    (L13156).
//  - DS5C1: 607Dh "applicable modes: NO" (L9821-L9822): not enforced.
//  - DS1000A-EC (after homing, L1404): a position beyond the range stops at the range (L1400);
//    from outside only motion toward it (L1402); a position-control setting (7.3, L1293).
// Lines: A6B panasonic-minas-a6b-ethercat-spec.zh.txt, DS5C1 xinje-ds5c1-user-manual.zh.md,
// DS1000A-EC ds1000a-ec-manual.ja.txt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

constexpr double kSpeedRpm = 300.0;   // 5 rev/s
constexpr double kQuickStopRevS2 = 20.0;

void profile_parameters(EngineBench& b) {
  b.set(0x6081, 0, std::llround(b.user_speed(kSpeedRpm)));
  b.set(0x6083, 0, std::llround(50 * b.per_rev()));
  b.set(0x6084, 0, std::llround(50 * b.per_rev()));
  b.set(0x6085, 0, std::llround(kQuickStopRevS2 * b.per_rev()));
  b.set(0x607F, 0, std::llround(b.user_speed(3000)));
  b.set(0x6067, 0, std::llround(b.per_rev() / 1000.0));
}

// 607Dh in revolutions of the user frame.
void soft_limits(EngineBench& b, double min_revs, double max_revs) {
  b.set(0x607D, 1, std::llround(min_revs * b.per_rev()));
  b.set(0x607D, 2, std::llround(max_revs * b.per_rev()));
}

// A pp set-point to `revs` (user frame), handshake done; the axis is then on its way.
void pp_target(EngineBench& b, double revs) {
  b.set(0x607A, 0, std::llround(revs * b.per_rev()));
  b.command(kCwEnable, 2 * kMs);
  b.command(kCwEnable | kCwNewSetPoint, 3 * kMs);
  b.command(kCwEnable, 1 * kMs);
}

double user_revs(const EngineBench& b) { return static_cast<double>(b.position()) / b.per_rev(); }

// Homing method 37 (current position, 607Ch = 0) from Operation enabled in hm, then enables pp.
void home_here_then_pp(EngineBench& b) {
  b.set(0x6098, 0, 37);
  b.set(0x607C, 0, 0);
  ASSERT_TRUE(b.enable(mode::hm)) << b.diag();
  b.command(kCwEnable | kCwNewSetPoint, 20 * kMs);
  ASSERT_EQ(b.status() & (sw::oms12 | sw::oms13), sw::oms12) << "homing attained " << b.diag();
  ASSERT_EQ(b.position(), 0);
  ASSERT_TRUE(b.enable(mode::pp)) << b.diag();
}

// A6B: before homing 607Dh does nothing; after it a move to +4 rev with 607Dh-02h = +2 rev
// decelerates at 6085h from +2 rev and stands at 2 + v^2 / (2 * 6085h) = 2.625 rev; bit 11 is 1
// there (outside the range); a move back toward the range starts at once, and bit 11 drops inside.
TEST(EngineSoftLimits, A6bDeceleratesByTheQuickStopRampAfterHoming) {
  EngineBench b("a6b");
  profile_parameters(b);
  ASSERT_TRUE(b.enable(mode::pp)) << b.diag();
  const double origin = user_revs(b);
  soft_limits(b, origin - 1.0, origin + 2.0);
  pp_target(b, origin + 3.0);
  b.run(2000 * kMs);
  EXPECT_NEAR(user_revs(b) - origin, 3.0, 0.005) << "not homed: 607Dh inactive (L13151) " << b.diag();
  EXPECT_EQ(b.status() & sw::internal_limit, 0);

  home_here_then_pp(b);  // position 0 here
  soft_limits(b, -1.0, 2.0);
  const double home_motor = b.motor_revs();
  pp_target(b, 4.0);
  double peak_rpm = 0.0;
  Nanos crossed = -1, stopped = -1;
  b.run(3000 * kMs, [&](Nanos now) {
    peak_rpm = std::max(peak_rpm, std::abs(b.motor_rpm()));
    if (crossed < 0 && b.get(0x6062) >= std::llround(2.0 * b.per_rev())) crossed = now;
    if (crossed >= 0 && stopped < 0 && b.get(0x606B) == 0) stopped = now;
  });
  const double overrun = (kSpeedRpm / 60.0) * (kSpeedRpm / 60.0) / (2.0 * kQuickStopRevS2);
  ASSERT_NEAR(peak_rpm, kSpeedRpm, 6.0) << "the move ran at 6081h before the limit";
  // The demand ramps down from the limit at 6085h: stands v^2/(2 a) beyond it. 0.01 rev: the
  // control step in which the demand crosses the limit (at 5 rev/s, 0.0006 rev) and the servo's
  // settling under the plant's friction.
  EXPECT_NEAR(b.motor_revs() - home_motor, 2.0 + overrun, 0.01) << "quick-stop ramp from the limit (L13212-L13218) "
                                                                  << b.diag();
  ASSERT_GE(crossed, 0);
  ASSERT_GE(stopped, 0);
  // v / a = 250 ms of ramp; the master sees 6062h/606Bh once per 1 ms cycle.
  EXPECT_NEAR(static_cast<double>(stopped - crossed) / 1e6, 1000.0 * (kSpeedRpm / 60.0) / kQuickStopRevS2, 2.0)
      << "the ramp is 6085h";
  EXPECT_NE(b.status() & sw::internal_limit, 0) << "bit 11: outside the normal range (L13167, L10131)";
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
  EXPECT_EQ(b.get(0x603F), 0) << b.diag();

  pp_target(b, 0.0);
  b.run(40 * kMs);
  EXPECT_LT(b.motor_revs() - home_motor, 2.0 + overrun - 0.01) << "motion back toward the range starts at once "
                                                                     "(L13163-L13165) "
                                                                  << b.diag();
  b.run(2000 * kMs);
  EXPECT_NEAR(b.motor_revs() - home_motor, 0.0, 0.005) << b.diag();
  EXPECT_EQ(b.status() & sw::internal_limit, 0) << "bit 11 back to 0 inside the range (L13167)";
}

// A6B: 607Dh acts in pp, ip and csp (L13145), not in pv: after homing pv runs past +2 rev.
TEST(EngineSoftLimits, A6bVelocityModeIsNotLimited) {
  EngineBench b("a6b");
  profile_parameters(b);
  home_here_then_pp(b);
  soft_limits(b, -1.0, 2.0);
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.set(0x60FF, 0, std::llround(b.user_speed(120)));
  b.run(2500 * kMs);  // 2 rev/s: about 4.5 rev
  EXPECT_GT(user_revs(b), 4.0) << b.diag();
  EXPECT_NEAR(b.motor_rpm(), 120.0, 2.4);
  EXPECT_EQ(b.status() & sw::internal_limit, 0) << b.diag();
}

// A6B: Init -> PreOp (incremental) leaves 607Dh inactive until the next homing (L13156).
TEST(EngineSoftLimits, A6bInitToPreOpNeedsHomingAgain) {
  EngineBench b("a6b");
  profile_parameters(b);
  home_here_then_pp(b);
  soft_limits(b, -1.0, 2.0);
  b.command(kCwShutdown, 20 * kMs);
  b.leave_op(ecat::AlState::Init);
  b.run(10 * kMs);
  b.to_op();
  ASSERT_TRUE(b.enable(mode::pp)) << b.diag();
  pp_target(b, 3.0);
  b.run(2000 * kMs);
  EXPECT_NEAR(user_revs(b), 3.0, 0.005) << "no limit before the next homing (L13156) " << b.diag();
}

// DS5C1: 607Dh is not applied in any mode (L9821-L9822), homed or not.
TEST(EngineSoftLimits, Ds5c1IgnoresThem) {
  EngineBench b("ds5c1");
  profile_parameters(b);
  home_here_then_pp(b);
  soft_limits(b, -1.0, 2.0);
  pp_target(b, 4.0);
  b.run(2500 * kMs);
  EXPECT_NEAR(user_revs(b), 4.0, 0.005) << b.diag();
  EXPECT_EQ(b.status() & sw::internal_limit, 0);
}

// DS1000A-EC: inactive until homed (L1404); then a target beyond 607Dh-02h stops at it (L1400)
// with bit 11 (internal limit, L1027-L1082 bit list; a software limit is what it reports), and from
// there only motion back toward the range (L1402) — which starts at once.
TEST(EngineSoftLimits, Ds1000aStopsAtTheLimitAfterHoming) {
  EngineBench b("ds1000a");
  profile_parameters(b);
  ASSERT_TRUE(b.enable(mode::pp)) << b.diag();
  soft_limits(b, -1.0, 2.0);
  pp_target(b, 3.0);
  b.run(2000 * kMs);
  EXPECT_NEAR(user_revs(b), 3.0, 0.005) << "not homed: inactive (L1404) " << b.diag();

  home_here_then_pp(b);
  soft_limits(b, -1.0, 2.0);
  const double home_motor = b.motor_revs();
  pp_target(b, 4.0);
  double furthest = 0.0;
  bool bit11 = false;
  b.run(2000 * kMs, [&](Nanos) {
    furthest = std::max(furthest, b.motor_revs() - home_motor);
    bit11 = bit11 || (b.status() & sw::internal_limit) != 0;
  });
  EXPECT_NEAR(b.motor_revs() - home_motor, 2.0, 0.005) << "stops at the limit (L1400) " << b.diag();
  // The servo's own overshoot when the demand stops at the limit: 0.02 rev (7 degrees).
  EXPECT_LT(furthest, 2.02) << "not carried beyond it";
  EXPECT_TRUE(bit11) << "internal limit active";
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();

  pp_target(b, 0.0);
  b.run(40 * kMs);
  EXPECT_LT(b.motor_revs() - home_motor, 1.99) << "back toward the range at once (L1402) " << b.diag();
  b.run(2000 * kMs);
  EXPECT_NEAR(b.motor_revs() - home_motor, 0.0, 0.005) << b.diag();
}

// DS1000A-EC: 607Dh is a position-control setting (7.3, L1293, L1387): pv is not limited.
TEST(EngineSoftLimits, Ds1000aVelocityModeIsNotLimited) {
  EngineBench b("ds1000a");
  profile_parameters(b);
  home_here_then_pp(b);
  soft_limits(b, -1.0, 2.0);
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.set(0x60FF, 0, std::llround(b.user_speed(120)));
  b.run(2500 * kMs);
  EXPECT_GT(user_revs(b), 4.0) << b.diag();
}

}  // namespace
}  // namespace vdrive::drive::test
