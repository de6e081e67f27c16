// Product-specific stops: the servo-side sequences behind code 0 and the alarms (A6B 3506h/3510h,
// DS5C1 P0-27/P0-29), the DS1000A-EC's CiA 402 "disable drive function", main power, STO / TO and
// the ESM falling to Init.
#include <gtest/gtest.h>

#include "tests/drive/pds/pds_bench.hpp"

namespace vdrive::test {
namespace {

using drive::DriveSideAction;
using drive::PdsState;
using drive::StopKind;

drive::PdsConditions alarm(drive::PdsConditions c, profile::AlarmReaction r, bool communication = false) {
  c.fault = true;
  c.fault_reaction = r;
  c.fault_is_communication = communication;
  return c;
}

TEST(PdsVendorStop, A6bShutdownCode0FollowsSequenceAtServoOff) {
  PdsBench b("a6b");
  b.set(0x605B, 0);
  b.set(0x3506, 1);                                // odd: free run (L26447-L26459)
  b.enable();
  b.step(kShutdown, 10.0);
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);   // still OE while it stops (L27242)
  EXPECT_EQ(b.pds.stop(), StopKind::DriveSide);
  EXPECT_EQ(b.pds.drive_side_action(), DriveSideAction::FreeRun);
  EXPECT_FALSE(b.pds.power_stage_on());
  EXPECT_EQ(b.pds.statusword(), 0x0037);           // bit 4 unchanged (L27249)
  b.step(kShutdown, 0.49);                         // below 30 r/min = 0.5 rev/s: stopped (L27244)
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);

  b.set(0x3506, 8);                                // immediate stop
  b.step(kEnable);
  b.step(kShutdown, 10.0);
  EXPECT_EQ(b.pds.drive_side_action(), DriveSideAction::ImmediateStop);
  EXPECT_TRUE(b.pds.power_stage_on());
}

TEST(PdsVendorStop, A6bAlarmsStopBySequenceAtAlarm) {
  PdsBench b("a6b");
  b.set(0x3510, 0);
  b.enable();
  b.step(kEnable, 10.0, alarm(b.base, profile::AlarmReaction::ImmediateStop));
  EXPECT_EQ(b.pds.stop(), StopKind::DriveSide);    // 605Eh does not apply (L27568-L27570)
  EXPECT_EQ(b.pds.drive_side_action(), DriveSideAction::DynamicBrake);

  PdsBench c("a6b");
  c.set(0x3510, 4);                                // 4-7: the "immediate stop" alarms stop at once (L32910)
  c.set(0x605E, 2);
  c.enable();
  c.step(kEnable, 10.0, alarm(c.base, profile::AlarmReaction::ImmediateStop));
  EXPECT_EQ(c.pds.drive_side_action(), DriveSideAction::ImmediateStop);
  EXPECT_TRUE(c.pds.power_stage_on());

  PdsBench d("a6b");
  d.set(0x3510, 5);
  d.enable();
  d.step(kEnable, 10.0, alarm(d.base, profile::AlarmReaction::FreeRun));   // no immediate-stop column
  EXPECT_EQ(d.pds.drive_side_action(), DriveSideAction::FreeRun);
}

TEST(PdsVendorStop, A6bCommunicationAlarmWith605Eh0UsesSequenceAtAlarm) {
  PdsBench b("a6b");
  b.set(0x605E, 0);
  b.set(0x3510, 3);
  b.enable();
  b.step(kEnable, 10.0, alarm(b.base, profile::AlarmReaction::ImmediateStop, true));
  EXPECT_EQ(b.pds.stop(), StopKind::DriveSide);    // L27542
  EXPECT_EQ(b.pds.drive_side_action(), DriveSideAction::FreeRun);
}

TEST(PdsVendorStop, Ds5c1ServoOffAndAlarmStops) {
  PdsBench b("ds5c1");
  b.set(0x605C, 0);
  b.set(0x201B, 2);                                // P0-27 = 2: decelerate (L2177, L8677)
  b.enable();
  b.step(kSwitchOn, 10.0);
  EXPECT_EQ(b.pds.stop(), StopKind::DriveSide);
  EXPECT_EQ(b.pds.drive_side_action(), DriveSideAction::Decelerate);
  EXPECT_TRUE(b.pds.power_stage_on());
  b.step(kSwitchOn, 0.15);                         // 10 r/min = 0.167 rev/s (L4428)
  EXPECT_EQ(b.pds.state(), PdsState::SwitchedOn);

  b.set(0x201B, 0);                                // P0-27 = 0 (default): coast (L2175)
  b.step(kEnable);
  b.step(kSwitchOn, 10.0);
  EXPECT_EQ(b.pds.drive_side_action(), DriveSideAction::FreeRun);
  EXPECT_FALSE(b.pds.power_stage_on());

  PdsBench a("ds5c1");                             // P0-29 = 2 (default, L2171)
  a.enable();
  a.step(kEnable, 10.0, alarm(a.base, profile::AlarmReaction::Deceleration));
  EXPECT_EQ(a.pds.drive_side_action(), DriveSideAction::Decelerate);   // "不关使能" alarm (L2234)
  PdsBench f("ds5c1");
  f.enable();
  f.step(kEnable, 10.0, alarm(f.base, profile::AlarmReaction::FreeRun));
  EXPECT_EQ(f.pds.drive_side_action(), DriveSideAction::FreeRun);      // "关使能" alarm (L2214-L2220)
}

TEST(PdsVendorStop, Ds5c1StopsAt10RpmNot30) {
  PdsBench b("ds5c1");
  ASSERT_DOUBLE_EQ(b.product.drive.stopped_speed_rpm, 10.0);           // L4428
  b.set(0x605B, 1);
  b.enable();
  b.step(kShutdown, 10.0);
  b.step(kShutdown, 0.4);                          // 24 r/min: an A6B would call it stopped
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  b.step(kShutdown, 0.16);
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);
}

TEST(PdsVendorStop, Ds1000aCode0DisablesTheDriveAtOnce) {
  PdsBench b("ds1000a");                           // 605Bh = 0 (L4901): no servo-side sequence
  EXPECT_FALSE(b.pds.vendor_stop().present());
  b.enable();
  b.step(kShutdown, 10.0);
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);
  EXPECT_FALSE(b.pds.power_stage_on());
  b.step(kEnable);
  b.set(0x605A, 0);
  b.step(kQuickStop, 10.0);                        // 11 and 12 together
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  // Its alarms are free run (605Eh = 0, L4907): the motor coasts in FRA until stopped.
  b.step(kShutdown);
  b.step(kEnable);
  b.step(kEnable, 10.0, alarm(b.base, profile::AlarmReaction::FreeRun));
  EXPECT_EQ(b.pds.state(), PdsState::FaultReactionActive);
  EXPECT_EQ(b.pds.stop(), StopKind::Coast);
  EXPECT_FALSE(b.pds.power_stage_on());
}

TEST(PdsVendorStop, ServoSideStopOutranksAFaultRamp) {
  PdsBench b("a6b");
  b.set(0x605B, 0);
  b.set(0x3506, 3);                                // free run
  b.set(0x605E, 2);
  b.enable();
  b.step(kShutdown, 10.0);
  b.step(kShutdown, 9.0, alarm(b.base, profile::AlarmReaction::ImmediateStop, true));
  EXPECT_EQ(b.pds.state(), PdsState::FaultReactionActive);
  EXPECT_EQ(b.pds.stop(), StopKind::DriveSide);    // L26482-L26502: servo-side > fault deceleration
  EXPECT_EQ(b.pds.drive_side_action(), DriveSideAction::FreeRun);
}

TEST(PdsVendorStop, FaultReplacesARunningQuickStop) {
  PdsBench b("ds1000a");
  b.set(0x605A, 6);
  b.set(0x605E, 1);
  b.enable();
  b.step(kQuickStop, 10.0);
  ASSERT_EQ(b.pds.stop(), StopKind::QuickStopRamp);
  b.step(kQuickStop, 9.0, alarm(b.base, profile::AlarmReaction::FreeRun, true));
  EXPECT_EQ(b.pds.state(), PdsState::FaultReactionActive);
  EXPECT_EQ(b.pds.stop(), StopKind::SlowDown);
  EXPECT_TRUE(b.pds.stop_started());
}

class PdsPowerInputs : public ::testing::TestWithParam<const char*> {
protected:
  PdsBench b{GetParam()};
};

TEST_P(PdsPowerInputs, TorqueOffForcesSwitchOnDisabledWithoutFault) {
  // A6B STO (L9436-L9438), DS1000A-EC TO input (L5566-L5572).
  b.enable();
  drive::PdsConditions c = b.base;
  c.torque_off = true;
  b.step(kEnable, 10.0, c);
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  EXPECT_FALSE(b.pds.power_stage_on());
  b.step(kShutdown, 0.0, c);                       // transition 2 refused while torque is off
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  c.torque_off = false;                            // L5574-L5582: release, then walk again
  b.step(kShutdown, 0.0, c);
  b.step(kSwitchOn, 0.0, c);
  b.step(kEnable, 0.0, c);
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  c.torque_off = true;
  b.step(kEnable, 0.0, c);
  b.step(kEnable, 0.0, c);
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  for (PdsState from : {PdsState::ReadyToSwitchOn, PdsState::SwitchedOn}) {
    c.torque_off = false;
    b.step(kShutdown, 0.0, c);
    if (from == PdsState::SwitchedOn) b.step(kSwitchOn, 0.0, c);
    ASSERT_EQ(b.pds.state(), from);
    c.torque_off = true;
    b.step(kSwitchOn, 0.0, c);                     // transitions 7 and 10
    EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  }
}

TEST_P(PdsPowerInputs, EsmInitForcesSwitchOnDisabledFromReadyAndSwitchedOn) {
  drive::PdsConditions c = b.base;
  b.step(kShutdown);
  c.esm_init = true;
  b.step(kShutdown, 0.0, c);                       // transition 7 (A6B L9667, DS5C1 L5989)
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  b.step(kShutdown, 0.0, c);                       // 6040h keeps its last value in Init: no way back
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  c.esm_init = false;
  b.step(kShutdown, 0.0, c);
  b.step(kSwitchOn, 0.0, c);
  c.esm_init = true;
  b.step(kSwitchOn, 0.0, c);                       // transition 10 (A6B L9703, DS5C1 L5992)
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
}

TEST_P(PdsPowerInputs, MainPowerLossInSwitchedOnIsTransition6) {
  b.step(kShutdown);
  b.step(kSwitchOn);
  drive::PdsConditions c = b.base;
  c.main_power = false;
  b.step(kSwitchOn, 0.0, c);                       // A6B L9655, DS5C1 L5988
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);
  EXPECT_EQ(b.pds.statusword(), 0x0021);
}

INSTANTIATE_TEST_SUITE_P(Products, PdsPowerInputs, ::testing::Values("a6b", "ds5c1", "ds1000a"));

TEST(PdsAbortConnection, A6bMainPowerOffWhileEnabledFollows6007h) {
  // 6007h (L26567-L26591): 2 = Disable voltage via 605Bh, 3 = Quick stop via 605Ah (then SOD even
  // with 5-7, L27061), 1 = fault, 0 = nothing here.
  PdsBench two("a6b");
  two.set(0x6007, 2);
  two.set(0x605B, 1);
  two.enable();
  drive::PdsConditions off = two.base;
  off.main_power = false;
  two.step(kEnable, 10.0, off);
  EXPECT_EQ(two.pds.state(), PdsState::OperationEnabled);
  EXPECT_EQ(two.pds.stop(), StopKind::SlowDown);
  EXPECT_EQ(two.pds.statusword(), 0x0027);         // bit 4 clear: no main power
  two.step(kEnable, 0.0, off);
  EXPECT_EQ(two.pds.state(), PdsState::SwitchOnDisabled);   // transition 9

  PdsBench three("a6b");
  three.set(0x6007, 3);
  three.set(0x605A, 6);
  three.enable();
  three.step(kEnable, 10.0, off);
  EXPECT_EQ(three.pds.state(), PdsState::QuickStopActive);
  EXPECT_EQ(three.pds.stop(), StopKind::QuickStopRamp);
  three.step(kEnable, 0.0, off);
  EXPECT_EQ(three.pds.state(), PdsState::SwitchOnDisabled);

  PdsBench one("a6b");
  one.set(0x6007, 1);
  one.enable();
  one.step(kEnable, 10.0, off);
  EXPECT_TRUE(one.pds.abort_connection_fault());
  EXPECT_EQ(one.pds.state(), PdsState::OperationEnabled);   // the alarm comes from the engine

  PdsBench zero("a6b");
  zero.enable();
  zero.step(kEnable, 10.0, off);
  EXPECT_FALSE(zero.pds.abort_connection_fault());
  EXPECT_EQ(zero.pds.state(), PdsState::OperationEnabled);
}

}  // namespace
}  // namespace vdrive::test
