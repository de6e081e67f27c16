// PreOp->SafeOp synchronisation checks per product: sync types (0x0028), DC activation (0x0030),
// cycle times (0x0035), and the A6B's rewrite of 1C32h/1C33h-01h from 0981h.
#include <gtest/gtest.h>

#include <cstdint>

#include "vdrive/firmware/sync/sync_check.hpp"
#include "vdrive/firmware/sync/sync_rules.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::firmware::sync {
namespace {

struct Product {
  profile::ProductProfile profile;
  SyncRules rules;
  explicit Product(const char* id) : profile(profile::load_profile(id)), rules(rules_for(profile)) {}
  SyncDecision check(const SyncSettings& s) const {
    return check_sync_settings(rules, profile.al_codes, rewrite_from_dc_activation(rules, s));
  }
};

SyncSettings dc(std::uint32_t sync0, std::uint32_t cycle, std::uint16_t out = 2, std::uint16_t in = 2) {
  return SyncSettings{kDcCyclicSync0, sync0, out, in, cycle};
}
SyncSettings sm2(std::uint32_t cycle, std::uint16_t out, std::uint16_t in) {
  return SyncSettings{0, 0, out, in, cycle};
}

TEST(SyncCheck, A6bAcceptsEachCycleOfErr810AndRefusesOthers) {
  const Product a6b("a6b");
  for (std::uint32_t c : {125000u, 250000u, 500000u, 1000000u, 2000000u, 4000000u, 8000000u, 10000000u}) {
    const SyncDecision d = a6b.check(dc(c, c));
    EXPECT_TRUE(d.result.ok()) << c;
    EXPECT_EQ(d.mode, SyncMode::DcSync0);
    EXPECT_EQ(d.cycle_ns, c);
  }
  for (std::uint32_t c : {0u, 100000u, 300000u, 3000000u, 12000000u}) {
    const SyncDecision d = a6b.check(dc(c, c));
    EXPECT_EQ(d.result.code, 0x0035) << c;
    EXPECT_EQ(d.result.fallback, ecat::AlState::PreOp);
  }
}

TEST(SyncCheck, A6bRefusesSync0CycleDifferentFrom1C32Cycle) {
  const Product a6b("a6b");
  EXPECT_EQ(a6b.check(dc(1000000, 2000000)).result.code, 0x0035);   // Err81.0: 09A0h != 1C32h-02h
  EXPECT_EQ(a6b.check(sm2(300000, 1, 0x22)).result.code, 0x0035);   // SM2: 1C32h-02h not in list
  EXPECT_TRUE(a6b.check(sm2(2000000, 1, 0x22)).result.ok());
}

// The rewrite and the SM2-input value are profile data (sync.sync_types_follow_dc_activation,
// sync.input_sm2_sync_type), not tied to a product.
TEST(SyncCheck, RewriteAndInputSm2TypeComeFromTheProfile) {
  profile::ProductProfile p = profile::load_profile("ds1000a");
  SyncSettings s = rewrite_from_dc_activation(rules_for(p), dc(1000000, 1000000, 0x00, 0x22));
  EXPECT_EQ(s.output_sync_type, 0x00);   // ds1000a: sync_types_follow_dc_activation false
  EXPECT_EQ(s.input_sync_type, 0x22);
  p.sync.sync_types_follow_dc_activation = true;
  s = rewrite_from_dc_activation(rules_for(p), dc(1000000, 1000000, 0x00, 0x22));
  EXPECT_EQ(s.output_sync_type, 0x02);
  EXPECT_EQ(s.input_sync_type, 0x02);
  p.sync.input_sm2_sync_type = 0x01;
  p.sync.sm3.accepted_sync_types = {0x00, 0x01, 0x02};
  EXPECT_TRUE(check_sync_settings(rules_for(p), p.al_codes, sm2(0, 0x01, 0x01)).result.ok());
  EXPECT_EQ(check_sync_settings(rules_for(p), p.al_codes, sm2(0, 0x01, 0x00)).result.code, 0x0028);
}

TEST(SyncCheck, A6bRewritesSyncTypesFromDcActivation) {
  const Product a6b("a6b");
  // DC on: 00h/01h -> 02h (1C33h 22h -> 02h).
  SyncSettings s = rewrite_from_dc_activation(a6b.rules, dc(1000000, 1000000, 0x00, 0x22));
  EXPECT_EQ(s.output_sync_type, 0x02);
  EXPECT_EQ(s.input_sync_type, 0x02);
  s = rewrite_from_dc_activation(a6b.rules, dc(1000000, 1000000, 0x01, 0x00));
  EXPECT_EQ(s.output_sync_type, 0x02);
  EXPECT_EQ(s.input_sync_type, 0x02);
  // DC off: 02h -> 00h, 01h stays.
  s = rewrite_from_dc_activation(a6b.rules, sm2(1000000, 0x02, 0x02));
  EXPECT_EQ(s.output_sync_type, 0x00);
  EXPECT_EQ(s.input_sync_type, 0x00);
  s = rewrite_from_dc_activation(a6b.rules, sm2(1000000, 0x01, 0x22));
  EXPECT_EQ(s.output_sync_type, 0x01);
  EXPECT_EQ(s.input_sync_type, 0x22);
}

TEST(SyncCheck, A6bSyncTypeErrors) {
  const Product a6b("a6b");
  EXPECT_EQ(a6b.check(dc(1000000, 1000000, 0x03, 0x02)).result.code, 0x0028);  // 03h not supported
  EXPECT_EQ(a6b.check(sm2(1000000, 0x00, 0x01)).result.code, 0x0028);          // 1C33h 01h not supported
  // Without DC only one of the two synchronous with SM2: Err81.6.
  EXPECT_EQ(a6b.check(sm2(1000000, 0x01, 0x00)).result.code, 0x0028);
  EXPECT_EQ(a6b.check(sm2(1000000, 0x00, 0x22)).result.code, 0x0028);
  EXPECT_TRUE(a6b.check(sm2(0, 0x00, 0x00)).result.ok());   // free run, cycle 0 allowed
  EXPECT_EQ(a6b.check(sm2(0, 0x00, 0x00)).mode, SyncMode::FreeRun);
}

TEST(SyncCheck, DcActivationOtherThanOffOrSync0IsRefusedWith0030) {
  for (const char* id : {"a6b", "ds5c1", "ds1000a"}) {
    const Product p(id);
    for (std::uint8_t act : {0x01, 0x02, 0x05, 0x07}) {
      SyncSettings s = dc(1000000, 1000000);
      s.dc_activation = act;
      if (act & 0x01) s.output_sync_type = s.input_sync_type = 0;   // keep the sync types valid
      const SyncDecision d = p.check(s);
      EXPECT_EQ(d.result.code, 0x0030) << id << " 0981h=" << int(act);
      EXPECT_EQ(d.result.fallback, ecat::AlState::PreOp);
    }
    // Upper bits of 0981h (activation options) do not matter.
    SyncSettings s = dc(1000000, 1000000);
    s.dc_activation = 0x33;
    EXPECT_TRUE(p.check(s).result.ok()) << id;
  }
}

TEST(SyncCheck, Ds5c1CyclesOfE810) {
  const Product ds5c1("ds5c1");
  for (std::uint32_t c : {1000000u, 2000000u, 4000000u, 8000000u, 10000000u})
    EXPECT_TRUE(ds5c1.check(dc(c, c)).result.ok()) << c;
  for (std::uint32_t c : {125000u, 250000u, 500000u, 3000000u})
    EXPECT_EQ(ds5c1.check(dc(c, c)).result.code, 0x0035) << c;
}

TEST(SyncCheck, Ds5c1UsesSyncType01ForInputsOnSm2AndDoesNotRewrite) {
  const Product ds5c1("ds5c1");
  EXPECT_TRUE(ds5c1.check(sm2(1000000, 0x01, 0x01)).result.ok());
  EXPECT_EQ(ds5c1.check(sm2(1000000, 0x01, 0x22)).result.code, 0x0028);   // E-816: 00/01/02 only
  // No rewrite: DC on with free-run objects stays free run.
  const SyncDecision d = ds5c1.check(dc(1000000, 1000000, 0x00, 0x00));
  EXPECT_TRUE(d.result.ok());
  EXPECT_EQ(d.mode, SyncMode::FreeRun);
}

TEST(SyncCheck, Ds1000aAcceptsWholeMillisecondsFromOne) {
  const Product ds1000a("ds1000a");
  // 1C32h-02h is read-only there: the drive takes 09A0h, whatever 02h holds.
  for (std::uint32_t c : {1000000u, 2000000u, 3000000u, 7000000u, 10000000u, 20000000u}) {
    const SyncDecision d = ds1000a.check(dc(c, 0));
    EXPECT_TRUE(d.result.ok()) << c;
    EXPECT_EQ(d.cycle_ns, c);
  }
  for (std::uint32_t c : {125000u, 500000u, 1500000u, 2000001u})
    EXPECT_EQ(ds1000a.check(dc(c, 0)).result.code, 0x0035) << c;
  // SM2: the interval is measured after SafeOp, nothing to check yet.
  EXPECT_TRUE(ds1000a.check(sm2(0, 0x01, 0x22)).result.ok());
  EXPECT_EQ(ds1000a.check(sm2(0, 0x03, 0x22)).result.code, 0x0028);   // DC SYNC1 not supported
}

TEST(SyncCheck, CycleTimeAcceptedFollowsListOrStep) {
  profile::SyncSpec list;
  list.cycle_times_ns = {250000, 1000000};
  list.cycle_min_ns = 250000;
  list.cycle_max_ns = 1000000;
  EXPECT_TRUE(cycle_time_accepted(list, 250000));
  EXPECT_FALSE(cycle_time_accepted(list, 500000));
  profile::SyncSpec step;
  step.cycle_step_ns = 500000;
  step.cycle_min_ns = 500000;
  step.cycle_max_ns = 2000000;
  EXPECT_TRUE(cycle_time_accepted(step, 1500000));
  EXPECT_FALSE(cycle_time_accepted(step, 2500000));
  EXPECT_FALSE(cycle_time_accepted(step, 750000));
}

}  // namespace
}  // namespace vdrive::firmware::sync
