// The ESM decision logic on its own, with scripted transition checks: every valid and invalid
// transition, unknown requests, error flag and acknowledge, Bootstrap and Explicit Device ID per
// product. Expected codes are the manuals' (A6B 8-2 L32952-L33933, DS5C1 L7109-L7139), written as
// literals on purpose.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "tests/support/product_profiles.hpp"
#include "vdrive/firmware/al_state_machine.hpp"

namespace vdrive::firmware {
namespace {

using S = ecat::AlState;

// Records what the machine asked for and answers with scripted results.
struct ScriptedHooks : TransitionHooks {
  CheckResult init_to_preop, init_to_boot, preop_to_safeop, safeop_to_op;
  std::vector<std::string> checks;
  std::vector<std::pair<S, S>> entered_log;

  CheckResult check_init_to_preop() override { checks.push_back("IP"); return init_to_preop; }
  CheckResult check_init_to_boot() override { checks.push_back("IB"); return init_to_boot; }
  CheckResult check_preop_to_safeop() override { checks.push_back("PS"); return preop_to_safeop; }
  CheckResult check_safeop_to_op() override { checks.push_back("SO"); return safeop_to_op; }
  void entered(S from, S to) override { entered_log.emplace_back(from, to); }
};

ecat::AlControl request(std::uint8_t state, bool ack = false, bool id = false) {
  return ecat::AlControl{state, ack, id};
}
ecat::AlControl request(S state, bool ack = false, bool id = false) {
  return request(static_cast<std::uint8_t>(state), ack, id);
}

class Esm {
public:
  explicit Esm(const profile::ProductProfile& p) : esm(EsmTraits::of(p)) { esm.reset(); }

  void write(ecat::AlControl c, std::uint16_t device_id = 0) { esm.on_al_control(c, device_id, hooks); }
  // Drives the machine up the ladder with passing checks.
  void bring_to(S target) {
    if (target == S::Init) return;
    if (target == S::Boot) { write(request(S::Boot)); return; }
    write(request(S::PreOp));
    if (target == S::PreOp) return;
    write(request(S::SafeOp));
    if (target == S::SafeOp) return;
    write(request(S::Op));
  }

  AlStateMachine esm;
  ScriptedHooks hooks;
};

// ---- valid transitions ---------------------------------------------------------------------

TEST(FirmwareAlStateMachine, PowerOnIsInitWithoutError) {
  Esm m(test::product("a6b"));
  EXPECT_EQ(m.esm.status_register(), 0x0001);
  EXPECT_EQ(m.esm.status_code_register(), 0x0000);
}

TEST(FirmwareAlStateMachine, WalksUpOneStepAtATimeRunningEachCheck) {
  Esm m(test::product("a6b"));
  m.write(request(S::PreOp));
  EXPECT_EQ(m.esm.status_register(), 0x0002);
  m.write(request(S::SafeOp));
  EXPECT_EQ(m.esm.status_register(), 0x0004);
  m.write(request(S::Op));
  EXPECT_EQ(m.esm.status_register(), 0x0008);
  EXPECT_EQ(m.hooks.checks, (std::vector<std::string>{"IP", "PS", "SO"}));
  const std::vector<std::pair<S, S>> expected = {
      {S::Init, S::PreOp}, {S::PreOp, S::SafeOp}, {S::SafeOp, S::Op}};
  EXPECT_EQ(m.hooks.entered_log, expected);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

struct DownCase {
  S from, to;
};

class FirmwareAlStateMachineDown : public ::testing::TestWithParam<DownCase> {};

TEST_P(FirmwareAlStateMachineDown, GoingDownIsAlwaysAllowedAndUnchecked) {
  const DownCase c = GetParam();
  Esm m(test::product("a6b"));
  m.bring_to(c.from);
  m.hooks.checks.clear();
  m.hooks.entered_log.clear();
  m.write(request(c.to));
  EXPECT_EQ(m.esm.state(), c.to);
  EXPECT_FALSE(m.esm.error());
  EXPECT_TRUE(m.hooks.checks.empty());
  ASSERT_EQ(m.hooks.entered_log.size(), 1u);
  EXPECT_EQ(m.hooks.entered_log[0], std::make_pair(c.from, c.to));
}

INSTANTIATE_TEST_SUITE_P(AllDownTransitions, FirmwareAlStateMachineDown,
                         ::testing::Values(DownCase{S::Op, S::SafeOp}, DownCase{S::Op, S::PreOp},
                                           DownCase{S::Op, S::Init}, DownCase{S::SafeOp, S::PreOp},
                                           DownCase{S::SafeOp, S::Init},
                                           DownCase{S::PreOp, S::Init},
                                           DownCase{S::Boot, S::Init}));

TEST(FirmwareAlStateMachine, SameStateRequestChangesNothing) {
  for (S s : {S::Init, S::PreOp, S::SafeOp, S::Op}) {
    Esm m(test::product("a6b"));
    m.bring_to(s);
    m.hooks.checks.clear();
    m.hooks.entered_log.clear();
    m.write(request(s));
    EXPECT_EQ(m.esm.state(), s) << name(s);
    EXPECT_FALSE(m.esm.error()) << name(s);
    EXPECT_TRUE(m.hooks.checks.empty()) << name(s);
    EXPECT_TRUE(m.hooks.entered_log.empty()) << name(s);
  }
}

// ---- invalid transitions (Err80.0 / 0x0011) -----------------------------------------------

struct InvalidCase {
  S from, requested, after;  // `after`: the state the manual leaves the slave in
};

class FirmwareAlStateMachineInvalid
    : public ::testing::TestWithParam<std::tuple<InvalidCase, std::string>> {};

TEST_P(FirmwareAlStateMachineInvalid, ReportsInvalidTransitionAndStaysOpFallsToSafeOp) {
  const auto& [c, product_id] = GetParam();
  Esm m(test::product(product_id));
  m.bring_to(c.from);
  ASSERT_EQ(m.esm.state(), c.from);
  m.hooks.checks.clear();
  m.write(request(c.requested));
  EXPECT_EQ(m.esm.state(), c.after);
  EXPECT_TRUE(m.esm.error());
  EXPECT_EQ(m.esm.status_code_register(), 0x0011);  // Err80.0 (A6B L33000); ETG for the others
  EXPECT_EQ(m.esm.status_register(), static_cast<std::uint16_t>(c.after) | 0x10);
  EXPECT_TRUE(m.hooks.checks.empty());
}

// A6B Err80.0 list (L32966-L33006); "stay, OP -> SafeOP".
INSTANTIATE_TEST_SUITE_P(
    LadderAndIntoBoot, FirmwareAlStateMachineInvalid,
    ::testing::Combine(
        ::testing::Values(InvalidCase{S::Init, S::SafeOp, S::Init},
                          InvalidCase{S::Init, S::Op, S::Init},
                          InvalidCase{S::PreOp, S::Op, S::PreOp},
                          InvalidCase{S::PreOp, S::Boot, S::PreOp},
                          InvalidCase{S::SafeOp, S::Boot, S::SafeOp},
                          InvalidCase{S::Op, S::Boot, S::SafeOp}),
        ::testing::Values(std::string("a6b"), std::string("ds5c1"), std::string("ds1000a"))));

// Out of Boot, only Boot -> Init is valid; products with a Boot state only.
INSTANTIATE_TEST_SUITE_P(
    OutOfBoot, FirmwareAlStateMachineInvalid,
    ::testing::Combine(::testing::Values(InvalidCase{S::Boot, S::Boot, S::Boot},
                                         InvalidCase{S::Boot, S::PreOp, S::Boot},
                                         InvalidCase{S::Boot, S::SafeOp, S::Boot},
                                         InvalidCase{S::Boot, S::Op, S::Boot}),
                       ::testing::Values(std::string("a6b"), std::string("ds1000a"))));

TEST(FirmwareAlStateMachine, InvalidTransitionFromOpStopsOutputsViaEntered) {
  Esm m(test::product("a6b"));
  m.bring_to(S::Op);
  m.hooks.entered_log.clear();
  m.write(request(S::Boot));
  ASSERT_EQ(m.hooks.entered_log.size(), 1u);
  EXPECT_EQ(m.hooks.entered_log[0], std::make_pair(S::Op, S::SafeOp));
}

// ---- unknown requested state (Err80.1 / E-801 / 0x0012) -------------------------------------

TEST(FirmwareAlStateMachine, UnknownRequestedStateFromEveryState) {
  for (const auto& id : {std::string("a6b"), std::string("ds5c1"), std::string("ds1000a")}) {
    for (S from : {S::Init, S::PreOp, S::SafeOp, S::Op}) {
      for (std::uint8_t value : {0, 5, 6, 7, 9, 10, 11, 12, 13, 14, 15}) {
        Esm m(test::product(id));
        m.bring_to(from);
        m.write(request(value));
        const S after = from == S::Op ? S::SafeOp : from;  // L33007-L33037, L7114
        EXPECT_EQ(m.esm.state(), after) << id << " " << name(from) << " " << int(value);
        EXPECT_TRUE(m.esm.error());
        EXPECT_EQ(m.esm.status_code_register(), 0x0012) << id;
      }
    }
  }
}

// ---- Bootstrap ----------------------------------------------------------------------------

TEST(FirmwareAlStateMachine, A6bEntersBootAfterTheBootMailboxCheck) {
  Esm m(test::product("a6b"));
  m.write(request(S::Boot));
  EXPECT_EQ(m.esm.status_register(), 0x0003);
  EXPECT_EQ(m.hooks.checks, std::vector<std::string>{"IB"});
  m.write(request(S::Init));
  EXPECT_EQ(m.esm.status_register(), 0x0001);
}

TEST(FirmwareAlStateMachine, Ds1000aBootMailboxFailureReports0015AndStaysInit) {
  Esm m(test::product("ds1000a"));
  m.hooks.init_to_boot = {0x0015, S::Init};
  m.write(request(S::Boot));
  EXPECT_EQ(m.esm.status_register(), 0x0011);  // Init | error
  EXPECT_EQ(m.esm.status_code_register(), 0x0015);
}

TEST(FirmwareAlStateMachine, Ds5c1RefusesBootWith0013AndStaysInit) {
  // E-802 (L7115): AL 0013h, ESM after the error: Init.
  Esm m(test::product("ds5c1"));
  m.write(request(S::Boot));
  EXPECT_EQ(m.esm.status_register(), 0x0011);
  EXPECT_EQ(m.esm.status_code_register(), 0x0013);
  EXPECT_TRUE(m.hooks.checks.empty());
}

// ---- transition checks --------------------------------------------------------------------

TEST(FirmwareAlStateMachine, FailedMailboxCheckLeavesInitWithItsCode) {
  Esm m(test::product("a6b"));
  m.hooks.init_to_preop = {0x0016, S::Init};
  m.write(request(S::PreOp));
  EXPECT_EQ(m.esm.status_register(), 0x0011);
  EXPECT_EQ(m.esm.status_code_register(), 0x0016);
  EXPECT_TRUE(m.hooks.entered_log.empty());
}

TEST(FirmwareAlStateMachine, FailedPreOpToSafeOpCheckStaysPreOp) {
  Esm m(test::product("a6b"));
  m.bring_to(S::PreOp);
  m.hooks.preop_to_safeop = {0x001D, S::PreOp};
  m.write(request(S::SafeOp));
  EXPECT_EQ(m.esm.status_register(), 0x0012);
  EXPECT_EQ(m.esm.status_code_register(), 0x001D);
}

TEST(FirmwareAlStateMachine, CheckMayDropTheSlaveLower) {
  Esm m(test::product("a6b"));
  m.bring_to(S::SafeOp);
  m.hooks.entered_log.clear();
  m.hooks.safeop_to_op = {0x0016, S::Init};
  m.write(request(S::Op));
  EXPECT_EQ(m.esm.status_register(), 0x0011);
  EXPECT_EQ(m.esm.status_code_register(), 0x0016);
  ASSERT_EQ(m.hooks.entered_log.size(), 1u);
  EXPECT_EQ(m.hooks.entered_log[0], std::make_pair(S::SafeOp, S::Init));
}

// ---- error flag and acknowledge --------------------------------------------------------------

TEST(FirmwareAlStateMachine, WithErrorPendingAHigherRequestWithoutAckIsIgnored) {
  Esm m(test::product("a6b"));
  m.bring_to(S::PreOp);
  m.write(request(S::Op));  // invalid: PreOp | error, 0x0011
  m.hooks.checks.clear();
  m.write(request(S::SafeOp));
  EXPECT_EQ(m.esm.status_register(), 0x0012);
  EXPECT_EQ(m.esm.status_code_register(), 0x0011);
  EXPECT_TRUE(m.hooks.checks.empty());
}

TEST(FirmwareAlStateMachine, AckWithAHigherRequestClearsTheErrorAndTransitions) {
  Esm m(test::product("a6b"));
  m.bring_to(S::PreOp);
  m.write(request(S::Op));
  m.write(request(S::SafeOp, /*ack=*/true));
  EXPECT_EQ(m.esm.status_register(), 0x0004);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

TEST(FirmwareAlStateMachine, AckWithTheSameStateClearsTheError) {
  Esm m(test::product("a6b"));
  m.bring_to(S::SafeOp);
  m.write(request(S::Boot));  // invalid: SafeOp | error
  m.write(request(S::SafeOp, /*ack=*/true));
  EXPECT_EQ(m.esm.status_register(), 0x0004);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

TEST(FirmwareAlStateMachine, AckWithALowerStateClearsTheErrorAndGoesDown) {
  Esm m(test::product("a6b"));
  m.bring_to(S::SafeOp);
  m.write(request(S::Boot));
  m.write(request(S::PreOp, /*ack=*/true));
  EXPECT_EQ(m.esm.status_register(), 0x0002);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

TEST(FirmwareAlStateMachine, WithErrorPendingALowerNonInitRequestWithoutAckIsIgnored) {
  Esm m(test::product("a6b"));
  m.bring_to(S::SafeOp);
  m.write(request(S::Boot));
  m.write(request(S::PreOp));
  EXPECT_EQ(m.esm.status_register(), 0x0014);
  EXPECT_EQ(m.esm.status_code_register(), 0x0011);
}

TEST(FirmwareAlStateMachine, InitRequestClearsTheErrorEvenWithoutAck) {
  Esm m(test::product("a6b"));
  m.hooks.init_to_preop = {0x0016, S::Init};
  m.write(request(S::PreOp));
  ASSERT_TRUE(m.esm.error());
  m.write(request(S::Init));
  EXPECT_EQ(m.esm.status_register(), 0x0001);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

TEST(FirmwareAlStateMachine, RetryAfterFixingTheMailboxNeedsAck) {
  Esm m(test::product("ds5c1"));
  m.hooks.init_to_preop = {0x0016, S::Init};
  m.write(request(S::PreOp));
  m.hooks.init_to_preop = CheckResult::pass();  // master fixed the SMs
  m.write(request(S::PreOp));                   // no ack: ignored
  EXPECT_EQ(m.esm.status_register(), 0x0011);
  m.write(request(S::PreOp, /*ack=*/true));
  EXPECT_EQ(m.esm.status_register(), 0x0002);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

TEST(FirmwareAlStateMachine, UnknownRequestWithErrorPendingIsIgnoredWithoutAck) {
  Esm m(test::product("a6b"));
  m.bring_to(S::PreOp);
  m.write(request(S::Op));        // 0x0011
  m.write(request(std::uint8_t{6}));  // would be 0x0012, but the error is not acknowledged
  EXPECT_EQ(m.esm.status_code_register(), 0x0011);
  m.write(request(std::uint8_t{6}, /*ack=*/true));  // acknowledged: the new request is judged
  EXPECT_EQ(m.esm.status_code_register(), 0x0012);
  EXPECT_EQ(m.esm.status_register(), 0x0012);
}

TEST(FirmwareAlStateMachine, AckWithoutErrorIsHarmless) {
  Esm m(test::product("a6b"));
  m.write(request(S::PreOp, /*ack=*/true));
  EXPECT_EQ(m.esm.status_register(), 0x0002);
}

TEST(FirmwareAlStateMachine, RaiseDropsToTheGivenStateWithError) {
  Esm m(test::product("a6b"));
  m.bring_to(S::Op);
  m.hooks.entered_log.clear();
  m.esm.raise(S::Init, 0x0016, m.hooks);
  EXPECT_EQ(m.esm.status_register(), 0x0011);
  EXPECT_EQ(m.esm.status_code_register(), 0x0016);
  ASSERT_EQ(m.hooks.entered_log.size(), 1u);
  EXPECT_EQ(m.hooks.entered_log[0], std::make_pair(S::Op, S::Init));
}

// ---- Explicit Device ID (A6B L5802-L5924) -----------------------------------------------------

TEST(FirmwareAlStateMachine, A6bIdRequestLoadsTheIdAndClearingBit5ClearsIt) {
  Esm m(test::product("a6b"));
  m.write(request(S::Init, false, /*id=*/true), 0x1234);
  EXPECT_EQ(m.esm.status_register(), 0x0021);
  EXPECT_EQ(m.esm.status_code_register(), 0x1234);
  m.write(request(S::PreOp, false, /*id=*/true), 0x1234);  // ID stays with a state change
  EXPECT_EQ(m.esm.status_register(), 0x0022);
  EXPECT_EQ(m.esm.status_code_register(), 0x1234);
  m.write(request(S::PreOp), 0x1234);
  EXPECT_EQ(m.esm.status_register(), 0x0002);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

TEST(FirmwareAlStateMachine, A6bErrorCodeHidesTheIdUntilAcknowledged) {
  Esm m(test::product("a6b"));
  m.bring_to(S::PreOp);
  m.write(request(S::Op, false, true), 0x0042);  // invalid transition with ID requested
  EXPECT_EQ(m.esm.status_register(), 0x0032);    // PreOp | error | ID loaded
  EXPECT_EQ(m.esm.status_code_register(), 0x0011);
  m.write(request(S::PreOp, true, true), 0x0042);
  EXPECT_EQ(m.esm.status_register(), 0x0022);
  EXPECT_EQ(m.esm.status_code_register(), 0x0042);
}

TEST(FirmwareAlStateMachine, Ds5c1IgnoresTheIdRequest) {
  Esm m(test::product("ds5c1"));
  m.write(request(S::Init, false, true), 0x1234);
  EXPECT_EQ(m.esm.status_register(), 0x0001);
  EXPECT_EQ(m.esm.status_code_register(), 0);
}

}  // namespace
}  // namespace vdrive::firmware
