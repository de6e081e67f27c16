// A product is data: Mixed402 exists only as files under tests/products/ (no code names it). It
// mixes rules of the three real products (Xinje vendor stop, A6B alarm reporting and soft-limit
// ramp, DS1000A-EC homing table, DS5C1 I/O rules). The normal loader reads it, the project master
// takes it to Op with DC at 1 ms and enables it in cyclic synchronous position: the statusword shows
// Operation enabled and the position follows a sine within the following-error window.
#include <gtest/gtest.h>

#include "master/cia402_program.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/csp_sine_run.hpp"
#include "tests/master/virtual_line.hpp"

namespace vdrive::master {
namespace {

network::NetworkOptions test_products() {
  network::NetworkOptions o;
  o.profile_dir = VDRIVE_TEST_PRODUCTS_DIR;
  return o;
}

TEST(MixedProduct, LoadsWithTheRulesItsFilesName) {
  test::VirtualLine line({"mixed402"}, test_products());
  const profile::ProductProfile& p = line.network().profile(0);
  EXPECT_EQ(p.identity.vendor_id, 0x00000402u);
  EXPECT_EQ(p.drive.vendor_stop.rule, profile::VendorStopRule::Xinje);
  EXPECT_EQ(p.drive.alarm_rules.error_register, profile::ErrorRegisterRule::AlStatusDefined);
  EXPECT_TRUE(p.drive.alarm_rules.emergency_sub_code);
  EXPECT_EQ(p.drive.io_rules, profile::IoRuleSet::DS5C1);
  EXPECT_EQ(p.drive.soft_limit_stop, profile::SoftLimitStop::Ramp);
  EXPECT_EQ(p.homing.vendor_methods, profile::HomingVendorMethods::TorqueLimit);
  EXPECT_EQ(p.homing.hard_stops.size(), 4u);
}

TEST(MixedProduct, MasterTakesItToOpAndItFollowsInCsp) {
  test::VirtualLine line({"mixed402"}, test_products());
  test::expect_lone_drive_follows_csp_sine(line);
}

}  // namespace
}  // namespace vdrive::master
