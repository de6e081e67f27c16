// Switching 6060h on the whole drive, per product, checked on 6061h and on what the motor does:
//  - A6B: switches in Operation enabled, 6061h shows the new mode about 2 ms later (L10609-L10611);
//    only at standstill (L10615-L10619: a switch during motion is not guaranteed, so not tested).
//  - DS5C1: switches in Operation enabled within 2 ms (L4369) except pp -> csp, refused (L4375-L4377).
//  - DS1000A-EC: 6061h changes only outside Operation enabled (switching there is "recommended";
//    in OE the drive "may briefly servo off", L1594-L1600: modelled as no switch in OE, profile
//    drive.mode_switch_while_enabled).
// Lines: A6B panasonic-minas-a6b-ethercat-spec.zh.txt, DS5C1 xinje-ds5c1-user-manual.zh.md,
// DS1000A-EC ds1000a-ec-manual.ja.txt.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

// 6061h once per bus cycle for `ms` cycles after writing 6060h = `m`.
std::vector<std::int64_t> request_mode(EngineBench& b, std::int8_t m, int ms) {
  std::vector<std::int64_t> seen;
  b.set(0x6060, 0, m);
  for (int i = 0; i < ms; ++i) {
    b.run(1 * kMs);
    seen.push_back(b.get(0x6061));
  }
  return seen;
}

void profile_parameters(EngineBench& b) {
  b.set(0x6081, 0, std::llround(b.user_speed(300)));
  b.set(0x6083, 0, std::llround(20 * b.per_rev()));
  b.set(0x6084, 0, std::llround(20 * b.per_rev()));
  b.set(0x607F, 0, std::llround(b.user_speed(3000)));
  b.set(0x6067, 0, std::llround(b.per_rev() / 1000.0));
}

// A pp move of `revs` from where the axis is, with the set-point handshake; true once target reached.
bool pp_move(EngineBench& b, double revs) {
  b.set(0x607A, 0, b.position() + std::llround(revs * b.per_rev()));
  b.command(kCwEnable, 2 * kMs);
  b.command(kCwEnable | kCwNewSetPoint, 3 * kMs);
  b.command(kCwEnable, 1 * kMs);
  return b.run_until([&] { return (b.status() & sw::target_reached) != 0; }, 3000 * kMs);
}

// A6B: pv standing -> pp in Operation enabled: 6061h still 3 one cycle later, 1 by the third
// (about 2 ms, L10609-L10611); the pp move then runs. Back to pv the same way, and the motor turns
// at 60FFh. The PDS stays Operation enabled throughout.
TEST(EngineModeSwitch, A6bSwitchesInOperationEnabledAfterAbout2ms) {
  EngineBench b("a6b");
  profile_parameters(b);
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.run(100 * kMs);
  const std::vector<std::int64_t> to_pp = request_mode(b, mode::pp, 4);
  EXPECT_EQ(to_pp[0], mode::pv) << "the switch takes about 2 ms (L10609)";
  EXPECT_EQ(to_pp[3], mode::pp) << "6061h shows the new mode after about 2 ms (L10609-L10611)";
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled);
  const double revs = b.motor_revs();
  ASSERT_TRUE(pp_move(b, 2.0)) << b.diag();
  EXPECT_NEAR(b.motor_revs() - revs, 2.0, 0.005) << "pp runs after the switch";

  const std::vector<std::int64_t> to_pv = request_mode(b, mode::pv, 4);
  EXPECT_EQ(to_pv[0], mode::pp);
  EXPECT_EQ(to_pv[3], mode::pv);
  b.set(0x60FF, 0, std::llround(b.user_speed(120)));
  b.run(800 * kMs);
  EXPECT_NEAR(b.motor_rpm(), 120.0, 2.4) << "pv runs after the switch " << b.diag();
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
  EXPECT_EQ(b.get(0x603F), 0);
}

// A6B: 6060h = 0 after a mode keeps that mode (L10631).
TEST(EngineModeSwitch, A6bZeroKeepsThePreviousMode) {
  EngineBench b("a6b");
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  const std::vector<std::int64_t> seen = request_mode(b, 0, 10);
  EXPECT_EQ(seen.back(), mode::pv) << b.diag();
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled);
  EXPECT_EQ(b.get(0x603F), 0) << "no Err88.1 for 0 after a mode";
}

// DS5C1: pp -> csp is refused in Operation enabled (L4375-L4377): 6061h stays 1 and pp still
// runs; pp -> pv is taken within 2 ms (L4369) and pv drives the motor.
TEST(EngineModeSwitch, Ds5c1RefusesPpToCspInOperationEnabled) {
  EngineBench b("ds5c1");
  profile_parameters(b);
  ASSERT_TRUE(b.enable(mode::pp)) << b.diag();
  b.run(100 * kMs);
  const std::vector<std::int64_t> to_csp = request_mode(b, mode::csp, 50);
  EXPECT_EQ(to_csp.back(), mode::pp) << "PP->CSP refused (L4375-L4377)";
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
  b.set(0x6060, 0, mode::pp);  // the master takes its request back
  const double revs = b.motor_revs();
  ASSERT_TRUE(pp_move(b, 1.0)) << b.diag();
  EXPECT_NEAR(b.motor_revs() - revs, 1.0, 0.005) << "still pp";

  const std::vector<std::int64_t> to_pv = request_mode(b, mode::pv, 3);
  EXPECT_EQ(to_pv[0], mode::pp);
  EXPECT_EQ(to_pv[2], mode::pv) << "position -> velocity in 2 ms (L4369)";
  b.set(0x60FF, 0, std::llround(b.user_speed(-120)));
  b.run(800 * kMs);
  EXPECT_NEAR(b.motor_rpm(), -120.0, 2.4) << b.diag();
  EXPECT_EQ(b.get(0x603F), 0);
}

// DS5C1: csp -> pp is allowed in Operation enabled (L4375-L4377).
TEST(EngineModeSwitch, Ds5c1SwitchesCspToPpInOperationEnabled) {
  EngineBench b("ds5c1");
  profile_parameters(b);
  ASSERT_TRUE(b.enable(mode::csp)) << b.diag();
  const std::int64_t hold = b.position();
  b.run(50 * kMs, [&](Nanos) { b.set(0x607A, 0, hold); });
  b.set(0x6060, 0, mode::pp);
  b.run(3 * kMs, [&](Nanos) { b.set(0x607A, 0, hold); });
  EXPECT_EQ(b.get(0x6061), mode::pp) << b.diag();
  const double revs = b.motor_revs();
  ASSERT_TRUE(pp_move(b, 1.0)) << b.diag();
  EXPECT_NEAR(b.motor_revs() - revs, 1.0, 0.005);
}

// DS1000A-EC: in Operation enabled 6061h keeps pv whatever 6060h says; after Disable operation
// (Switched on) it takes pp at once, and after Enable operation pp moves the axis (L1594-L1600).
TEST(EngineModeSwitch, Ds1000aChangesModeOnlyOutsideOperationEnabled) {
  EngineBench b("ds1000a");
  profile_parameters(b);
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.run(100 * kMs);
  const std::vector<std::int64_t> in_oe = request_mode(b, mode::pp, 100);
  EXPECT_EQ(in_oe.back(), mode::pv) << "no switch in Operation enabled";
  b.set(0x60FF, 0, std::llround(b.user_speed(60)));
  b.run(500 * kMs);
  EXPECT_NEAR(b.motor_rpm(), 60.0, 1.2) << "still pv " << b.diag();
  b.set(0x60FF, 0, 0);
  b.run(500 * kMs);

  b.command(kCwSwitchOn, 20 * kMs);  // Disable operation
  ASSERT_EQ(b.engine().state(), PdsState::SwitchedOn) << b.diag();
  EXPECT_EQ(b.get(0x6061), mode::pp) << "outside Operation enabled the request is taken";
  b.command(kCwEnable, 20 * kMs);
  ASSERT_EQ(b.engine().state(), PdsState::OperationEnabled) << b.diag();
  const double revs = b.motor_revs();
  ASSERT_TRUE(pp_move(b, 1.0)) << b.diag();
  EXPECT_NEAR(b.motor_revs() - revs, 1.0, 0.005);
}

}  // namespace
}  // namespace vdrive::drive::test
