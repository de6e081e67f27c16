// PdsMachine: states, transitions 0-16 and the controlword command table on all three products
// (A6B L9618-L9781 / L9849-L9906 / L10023-L10039, DS5C1 L5980-L5998 / L9382-L9439, DS1000A-EC
// L894-L984 / L1068-L1082).
#include <gtest/gtest.h>

#include "tests/drive/pds/pds_bench.hpp"

namespace vdrive::test {
namespace {

using drive::PdsState;
using drive::StopKind;

class PdsTransitions : public ::testing::TestWithParam<const char*> {
protected:
  PdsBench b{GetParam()};
};

TEST_P(PdsTransitions, PowerOnPassesNotReadyToSwitchOnToSwitchOnDisabled) {
  drive::PdsMachine fresh(b.ctx);
  EXPECT_EQ(fresh.state(), PdsState::NotReadyToSwitchOn);
  EXPECT_EQ(fresh.statusword(), 0x0000);          // x0xx 0000
  fresh.step(kShutdown, b.base);                  // nothing moves it before power_on (transitions 0, 1)
  EXPECT_EQ(fresh.state(), PdsState::NotReadyToSwitchOn);
  fresh.power_on();
  EXPECT_EQ(fresh.state(), PdsState::SwitchOnDisabled);
  EXPECT_EQ(fresh.statusword(), 0x0050);          // x1xx 0000 + bit 4 main power
}

TEST_P(PdsTransitions, WalkShowsTheStatuswordOfEachState) {
  // A6B getting-started walk L1718-L1751 (with main power: bit 4 set).
  EXPECT_EQ(b.pds.statusword(), 0x0050);
  b.step(kShutdown);                              // transition 2
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);
  EXPECT_EQ(b.pds.statusword(), 0x0031);
  b.step(kSwitchOn);                              // transition 3
  EXPECT_EQ(b.pds.state(), PdsState::SwitchedOn);
  EXPECT_EQ(b.pds.statusword(), 0x0033);
  EXPECT_FALSE(b.pds.enabled_event());
  b.step(kEnable);                                // transition 4
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  EXPECT_EQ(b.pds.statusword(), 0x0037);
  EXPECT_TRUE(b.pds.enabled_event());
  EXPECT_TRUE(b.pds.power_stage_on());
  EXPECT_TRUE(b.pds.motion_allowed());
  b.step(kEnable);
  EXPECT_FALSE(b.pds.enabled_event());            // an event, not a level
}

TEST_P(PdsTransitions, WithoutMainPowerBit4IsClear) {
  b.base.main_power = false;
  b.step(kShutdown);
  EXPECT_EQ(b.pds.statusword(), 0x0021);          // L1720: xx40h -> xx21h
  b.step(kSwitchOn);                              // transition 3 needs main power
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);
  b.base.main_power = true;
  b.step(kSwitchOn);
  EXPECT_EQ(b.pds.statusword(), 0x0033);
}

TEST_P(PdsTransitions, SwitchOnPlusEnableOperationInOneStep) {
  b.step(kShutdown);
  b.step(kEnable);                                // 3 + 4 (L9849ff *1, DS1000A-EC L974)
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  EXPECT_TRUE(b.pds.enabled_event());
}

TEST_P(PdsTransitions, SwitchOnDisabledAcceptsOnlyShutdown) {
  for (std::uint16_t cw : {kSwitchOn, kEnable, kQuickStop, kDisableVoltage, std::uint16_t{0x000B}}) {
    b.step(cw);
    EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled) << cw;
  }
}

TEST_P(PdsTransitions, DisableVoltageAndQuickStopLeaveReadyAndSwitchedOn) {
  for (std::uint16_t cw : {kDisableVoltage, kQuickStop, std::uint16_t{0x0004}, std::uint16_t{0x0008}}) {
    b.step(kShutdown);
    b.step(cw);                                   // transition 7
    EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled) << cw;
    b.step(kShutdown);
    b.step(kSwitchOn);
    b.step(cw);                                   // transition 10
    EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled) << cw;
  }
}

TEST_P(PdsTransitions, ShutdownFromSwitchedOnIsTransition6) {
  b.step(kShutdown);
  b.step(kSwitchOn);
  b.step(kShutdown);
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);
}

TEST_P(PdsTransitions, DisableOperationDeceleratesInOperationEnabledThenSwitchedOn) {
  b.set(0x605C, 1);                               // 6084h ramp (A6B L27312, DS5C1 L4462)
  b.enable();
  b.step(kSwitchOn, 10.0);                        // A: decelerate, state stays OE (L27362-L27364)
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  EXPECT_EQ(b.pds.statusword(), 0x0037);
  EXPECT_EQ(b.pds.stop(), StopKind::SlowDown);
  EXPECT_TRUE(b.pds.stop_started());
  EXPECT_TRUE(b.pds.power_stage_on());
  EXPECT_FALSE(b.pds.motion_allowed());           // the mode must not produce set-points now
  b.step(kSwitchOn, 5.0);
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  EXPECT_FALSE(b.pds.stop_started());
  b.step(kSwitchOn, 0.0);                         // B: stopped -> transition 5 (L27366-L27368)
  EXPECT_EQ(b.pds.state(), PdsState::SwitchedOn);
  EXPECT_EQ(b.pds.stop(), StopKind::None);
  EXPECT_FALSE(b.pds.power_stage_on());
}

TEST_P(PdsTransitions, ShutdownAndDisableVoltageDecelerateThenChangeState) {
  b.set(0x605B, 1);
  b.enable();
  b.step(kShutdown, 10.0);                        // transition 8 after the stop (L27240-L27246)
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  EXPECT_EQ(b.pds.stop(), StopKind::SlowDown);
  b.step(kShutdown, 0.0);
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);

  b.step(kEnable);
  ASSERT_EQ(b.pds.state(), PdsState::OperationEnabled);
  b.step(kDisableVoltage, 10.0);                  // transition 9 after the 605Bh stop (L27189-L27195)
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  b.step(kDisableVoltage, 0.0);
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
}

TEST_P(PdsTransitions, ALaterDisableVoltageDuringAShutdownStopEndsInSwitchOnDisabled) {
  b.set(0x605B, 1);
  b.enable();
  b.step(kShutdown, 10.0);
  b.step(kDisableVoltage, 8.0);
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  b.step(kDisableVoltage, 0.0);
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
}

TEST_P(PdsTransitions, QuickStopCodes0To3EndInSwitchOnDisabled) {
  b.set(0x605A, 2);                               // 6085h, then Switch on disabled (L27013)
  b.enable();
  b.step(kQuickStop, 10.0);                       // transition 11: QSA at once (L27094-L27096)
  EXPECT_EQ(b.pds.state(), PdsState::QuickStopActive);
  EXPECT_EQ(b.pds.statusword(), 0x0017);          // x00x 0111 + bit 4
  EXPECT_EQ(b.pds.stop(), StopKind::QuickStopRamp);
  EXPECT_TRUE(b.pds.power_stage_on());
  b.step(kEnable, 5.0);                           // no transition 16 with codes 0-3
  EXPECT_EQ(b.pds.state(), PdsState::QuickStopActive);
  EXPECT_FALSE(b.pds.enabled_event());
  b.step(kEnable, 0.0);                           // stopped -> transition 12 (L9723-L9725)
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  EXPECT_FALSE(b.pds.power_stage_on());
}

TEST_P(PdsTransitions, QuickStopCodes5To7StayAndEnableOperationReturns) {
  b.set(0x605A, 6);                               // 6085h, then stay in QSA (L27019)
  b.enable();
  b.step(kQuickStop, 10.0);
  b.step(kQuickStop, 0.0);
  EXPECT_EQ(b.pds.state(), PdsState::QuickStopActive);
  EXPECT_EQ(b.pds.stop(), StopKind::QuickStopRamp);  // the stop holds standstill
  EXPECT_TRUE(b.pds.power_stage_on());
  b.step(kQuickStop, 0.0);
  EXPECT_EQ(b.pds.state(), PdsState::QuickStopActive);
  b.step(kEnable, 0.0);                           // transition 16 (L9773-L9775)
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  EXPECT_TRUE(b.pds.enabled_event());
  EXPECT_TRUE(b.pds.motion_allowed());
}

TEST_P(PdsTransitions, QuickStopCodes5To7LeaveByDisableVoltageAfterTheStop) {
  b.set(0x605A, 5);
  b.enable();
  b.step(kQuickStop, 10.0);
  b.step(kDisableVoltage, 9.0);                   // during the stop: waits for it (L9727-L9731)
  EXPECT_EQ(b.pds.state(), PdsState::QuickStopActive);
  b.step(kDisableVoltage, 0.0);
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
}

TEST_P(PdsTransitions, FaultResetActsOnTheRisingEdgeOnlyWhenAllowed) {
  b.enable();
  drive::PdsConditions c = b.base;
  c.fault = true;
  c.fault_reaction = profile::AlarmReaction::FreeRun;
  b.step(kEnable, 0.0, c);                        // 13 and, already stopped, 14
  ASSERT_EQ(b.pds.state(), PdsState::Fault);
  EXPECT_EQ(b.pds.statusword(), 0x0018);
  b.step(kFaultReset, 0.0, c);                    // edge, but the alarm manager refuses
  EXPECT_EQ(b.pds.state(), PdsState::Fault);
  c.fault_reset_allowed = true;
  b.step(kFaultReset, 0.0, c);                    // bit 7 held: no edge
  EXPECT_EQ(b.pds.state(), PdsState::Fault);
  EXPECT_FALSE(b.pds.fault_reset_event());
  b.step(0x0000, 0.0, c);
  b.step(kFaultReset, 0.0, c);                    // 0 -> 1: transition 15
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  EXPECT_TRUE(b.pds.fault_reset_event());
  c.fault = false;                                // the alarm manager clears on the event
  b.step(kFaultReset, 0.0, c);
  EXPECT_FALSE(b.pds.fault_reset_event());
  EXPECT_EQ(b.pds.state(), PdsState::SwitchOnDisabled);
  b.step(kShutdown, 0.0, c);
  EXPECT_EQ(b.pds.state(), PdsState::ReadyToSwitchOn);
}

TEST_P(PdsTransitions, FaultResetBitMasksTheOtherCommands) {
  b.enable();
  b.step(0x0080 | kEnable);                       // bit 7 = 1: not a row of the table but Fault reset
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
  b.step(0x0080);                                 // would be Disable voltage with bit 7 = 0
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
}

TEST_P(PdsTransitions, AlarmInAnUnpoweredStateGoesStraightToFault) {
  b.step(kShutdown);
  drive::PdsConditions c = b.base;
  c.fault = true;
  c.fault_reaction = profile::AlarmReaction::FreeRun;
  b.step(kShutdown, 0.0, c);                      // 13 + 14: nothing to stop
  EXPECT_EQ(b.pds.state(), PdsState::Fault);
  EXPECT_EQ(b.pds.stop(), StopKind::None);
}

TEST_P(PdsTransitions, FaultReactionActiveUntilTheAxisStops) {
  b.enable();
  drive::PdsConditions c = b.base;
  c.fault = true;
  c.fault_reaction = profile::AlarmReaction::FreeRun;
  b.step(kEnable, 20.0, c);                       // A: alarm, FRA while decelerating (L27608-L27610)
  EXPECT_EQ(b.pds.state(), PdsState::FaultReactionActive);
  EXPECT_EQ(b.pds.statusword(), 0x001F);          // x0xx 1111 + bit 4
  EXPECT_TRUE(b.pds.stop_started());
  b.step(kFaultReset, 10.0, c);                   // not clearable during FRA (L34093)
  EXPECT_EQ(b.pds.state(), PdsState::FaultReactionActive);
  b.step(kEnable, 0.0, c);                        // B: stopped -> Fault, transition 14 (L27612-L27614)
  EXPECT_EQ(b.pds.state(), PdsState::Fault);
  EXPECT_EQ(b.pds.stop(), StopKind::None);
  EXPECT_FALSE(b.pds.power_stage_on());
}

TEST_P(PdsTransitions, AlarmWithReactionNoneLeavesThePdsAlone) {
  b.enable();
  drive::PdsConditions c = b.base;
  c.fault = true;
  c.fault_reaction = profile::AlarmReaction::None;
  b.step(kEnable, 0.0, c);
  EXPECT_EQ(b.pds.state(), PdsState::OperationEnabled);
}

INSTANTIATE_TEST_SUITE_P(Products, PdsTransitions, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::test
