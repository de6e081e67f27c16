// Which stop each option code starts, per product and mode (A6B L26997-L27570, DS5C1 L9441-L9604,
// DS1000A-EC L4899-L4907 with the CiA 402 meanings), and values outside a product's set.
#include <gtest/gtest.h>

#include "tests/drive/pds/pds_bench.hpp"
#include "vdrive/drive/pds/option_codes.hpp"

namespace vdrive::test {
namespace {

using drive::StopKind;
namespace mode = drive::mode;

TEST(PdsOptionCodes, QuickStopCodesPerModeFamily) {
  // pp, csp, csv, pv (A6B L27005-L27021): 1/5 6084h, 2/6 6085h, 3/7 60C6h.
  for (std::int8_t m : {mode::pp, mode::csp, mode::csv, mode::pv, mode::hm}) {
    EXPECT_EQ(drive::quick_stop_kind(1, m, true), StopKind::SlowDown);
    EXPECT_EQ(drive::quick_stop_kind(5, m, true), StopKind::SlowDown);
    EXPECT_EQ(drive::quick_stop_kind(2, m, true), StopKind::QuickStopRamp);
    EXPECT_EQ(drive::quick_stop_kind(6, m, true), StopKind::QuickStopRamp);
    EXPECT_EQ(drive::quick_stop_kind(3, m, true), StopKind::CurrentLimit);
    EXPECT_EQ(drive::quick_stop_kind(7, m, true), StopKind::CurrentLimit);
  }
  // tq, cst (L27045-L27057): 3 and 7 stop by torque 0.
  for (std::int8_t m : {mode::tq, mode::cst}) {
    EXPECT_EQ(drive::quick_stop_kind(3, m, true), StopKind::ZeroTorque);
    EXPECT_EQ(drive::quick_stop_kind(7, m, true), StopKind::ZeroTorque);
    EXPECT_EQ(drive::quick_stop_kind(2, m, true), StopKind::QuickStopRamp);  // 6087h (StopSequence)
  }
  // 0: the servo-side sequence (L27009), or CiA 402 "disable drive function" without one.
  EXPECT_EQ(drive::quick_stop_kind(0, mode::csp, true), StopKind::DriveSide);
  EXPECT_EQ(drive::quick_stop_kind(0, mode::csp, false), StopKind::Coast);
  EXPECT_FALSE(drive::quick_stop_stays_active(3));
  EXPECT_TRUE(drive::quick_stop_stays_active(5));
}

TEST(PdsOptionCodes, ShutdownHaltAndFaultReactionCodes) {
  EXPECT_EQ(drive::shutdown_kind(0, mode::pp, true), StopKind::DriveSide);  // 3506h (L27165)
  EXPECT_EQ(drive::shutdown_kind(1, mode::pp, true), StopKind::SlowDown);   // 6084h (L27167)
  EXPECT_EQ(drive::shutdown_kind(0, mode::pp, false), StopKind::Coast);
  EXPECT_EQ(drive::halt_kind(1, mode::pv), StopKind::SlowDown);             // L27420
  EXPECT_EQ(drive::halt_kind(2, mode::pv), StopKind::QuickStopRamp);        // L27422
  EXPECT_EQ(drive::halt_kind(3, mode::pv), StopKind::CurrentLimit);         // 6072h + 60C6h, L27424
  EXPECT_EQ(drive::halt_kind(3, mode::cst), StopKind::ZeroTorque);          // L27442
  EXPECT_EQ(drive::fault_reaction_kind(0, mode::csp, true), StopKind::DriveSide);     // 3510h, L27542
  EXPECT_EQ(drive::fault_reaction_kind(1, mode::csp, true), StopKind::SlowDown);      // L27544
  EXPECT_EQ(drive::fault_reaction_kind(2, mode::csp, true), StopKind::QuickStopRamp); // L27546
  EXPECT_EQ(drive::fault_reaction_kind(0, mode::csp, false), StopKind::Coast);        // DS1000A-EC
}

TEST(PdsOptionCodes, TheDictionaryDefaultsAreRead) {
  PdsBench ds1000a("ds1000a");
  EXPECT_EQ(ds1000a.pds.option_codes().quick_stop(), 2);     // L4899
  EXPECT_EQ(ds1000a.pds.option_codes().halt(), 1);           // L4905
  EXPECT_EQ(ds1000a.pds.option_codes().fault_reaction(), 0); // L4907
  EXPECT_EQ(ds1000a.pds.option_codes().abort_connection(), 0);  // no 6007h (L5241)
}

TEST(PdsOptionCodes, CodesTheProductDoesNotDefineKeepThePreviousBehaviour) {
  PdsBench a6b("a6b");
  a6b.set(0x605A, 6);
  a6b.step(0);
  ASSERT_EQ(a6b.pds.option_codes().quick_stop(), 6);
  for (std::int64_t bad : {4, -1, -2, 8, 100}) {   // 4 and -1/-2 "设定禁止" / manufacturer (L27001-L27007)
    a6b.set(0x605A, bad);
    a6b.step(0);
    EXPECT_EQ(a6b.pds.option_codes().quick_stop(), 6) << bad;
  }
  a6b.set(0x605D, 0);                              // 605Dh is 1-3 (L27410)
  a6b.step(0);
  EXPECT_EQ(a6b.pds.option_codes().halt(), 1);
  a6b.set(0x605E, 3);                              // 605Eh is 0-2 (L27530)
  a6b.step(0);
  EXPECT_EQ(a6b.pds.option_codes().fault_reaction(), 0);

  // The quick stop then still behaves as 6: QSA is kept after the stop.
  a6b.enable();
  a6b.step(kQuickStop, 0.0);
  a6b.step(kQuickStop, 0.0);
  EXPECT_EQ(a6b.pds.state(), drive::PdsState::QuickStopActive);
}

TEST(PdsOptionCodes, Ds5c1HasNoManufacturerQuickStopCodes) {
  PdsBench ds5c1("ds5c1");                         // 605Ah 0-7 (L4419)
  ds5c1.set(0x605A, 1);
  ds5c1.step(0);
  ds5c1.set(0x605A, -1);
  ds5c1.step(0);
  EXPECT_EQ(ds5c1.pds.option_codes().quick_stop(), 1);
  // 605Bh/605Ch are I8 on the DS5C1 (L4438, L4461) and still read right.
  ds5c1.set(0x605B, 1);
  ds5c1.set(0x605C, 1);
  ds5c1.step(0);
  EXPECT_EQ(ds5c1.pds.option_codes().shutdown(), 1);
  EXPECT_EQ(ds5c1.pds.option_codes().disable_operation(), 1);
}

class PdsStopChoice : public ::testing::TestWithParam<const char*> {
protected:
  PdsBench b{GetParam()};
};

TEST_P(PdsStopChoice, QuickStopInTorqueModeWithCode3DropsTheTorque) {
  b.set(0x605A, 3);
  b.base.mode = mode::tq;
  b.enable();
  b.step(kQuickStop, 10.0);
  EXPECT_EQ(b.pds.stop(), StopKind::ZeroTorque);
  EXPECT_TRUE(b.pds.power_stage_on());
}

TEST_P(PdsStopChoice, QuickStopInHomingWithCode1IsTheSlowDownRamp) {
  b.set(0x605A, 1);
  b.base.mode = mode::hm;
  b.enable();
  b.step(kQuickStop, 10.0);
  EXPECT_EQ(b.pds.stop(), StopKind::SlowDown);     // StopSequence picks 609Ah in hm (L27031)
}

TEST_P(PdsStopChoice, CommunicationAlarmStopsBy605Eh) {
  b.set(0x605E, 2);                                // 6085h (A6B L27546, DS5C1 L9593)
  b.enable();
  drive::PdsConditions c = b.base;
  c.fault = true;
  c.fault_is_communication = true;
  c.fault_reaction = profile::AlarmReaction::ImmediateStop;
  b.step(kEnable, 10.0, c);
  EXPECT_EQ(b.pds.state(), drive::PdsState::FaultReactionActive);
  EXPECT_EQ(b.pds.stop(), StopKind::QuickStopRamp);
  EXPECT_TRUE(b.pds.power_stage_on());
}

INSTANTIATE_TEST_SUITE_P(Products, PdsStopChoice, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::test
