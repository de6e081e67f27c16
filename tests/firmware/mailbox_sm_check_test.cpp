// The mailbox SyncManager rules, one violation at a time, per product (A6B Err81.1 L33400-L33446,
// DS5C1 E-811 L7125).
#include <gtest/gtest.h>

#include <array>

#include "tests/support/product_profiles.hpp"
#include "vdrive/firmware/mailbox_sm_check.hpp"

namespace vdrive::firmware {
namespace {

using test::product;

SmChannel sm(std::uint16_t start, std::uint16_t length, std::uint8_t control, bool enabled) {
  SmChannel c;
  c.start = start;
  c.length = length;
  c.control = control;
  c.activate = enabled ? 0x01 : 0x00;
  return c;
}

// What TwinCAT/SOEM write from the SII: SM0 0x1000/256 0x26, SM1 0x1200/256 0x22, SM2/SM3
// process data behind them (3-buffer: 3 x length each).
std::array<SmChannel, 4> good_layout() {
  return {sm(0x1000, 256, 0x26, true), sm(0x1200, 256, 0x22, true), sm(0x1400, 9, 0x64, true),
          sm(0x1600, 23, 0x20, true)};
}

MailboxSmFault check(const std::array<SmChannel, 4>& sms, const profile::MailboxSmRules& rules) {
  return check_mailbox_sms(sms, rules);
}

TEST(FirmwareMailboxSmCheck, AcceptsTheSiiLayoutOnA6bAndDs5c1) {
  EXPECT_EQ(check(good_layout(), product("a6b").mailbox_rules), MailboxSmFault::Ok);
  EXPECT_EQ(check(good_layout(), product("ds5c1").mailbox_rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, EachMailboxSmMustBeEnabled) {
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[0].activate = 0;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm0Disabled);
  sms = good_layout();
  sms[1].activate = 0;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Disabled);
}

TEST(FirmwareMailboxSmCheck, A6bLengthBelow32IsRejected) {
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[0].length = 31;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm0Length);
  sms[0].length = 32;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
  sms = good_layout();
  sms[1].length = 31;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Length);
}

TEST(FirmwareMailboxSmCheck, Ds5c1LengthWindows) {
  // SM0 32..256, SM1 40..256 (L7125).
  const auto rules = product("ds5c1").mailbox_rules;
  auto sms = good_layout();
  sms[0].length = 257;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm0Length);
  sms = good_layout();
  sms[1].length = 39;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Length);
  sms[1].length = 40;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
  sms[1].length = 257;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Length);
}

TEST(FirmwareMailboxSmCheck, Ds5c1StartWindows) {
  // SM0 start 1000h..10FFh, SM1 start 1200h..12FFh (L7125).
  const auto rules = product("ds5c1").mailbox_rules;
  auto sms = good_layout();
  sms[0].start = 0x1100;
  sms[0].length = 32;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm0Start);
  sms = good_layout();
  sms[1].start = 0x1300;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Start);
  sms[1].start = 0x1180;  // below the window, and not overlapping SM0 if SM0 is short
  sms[0].length = 64;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Start);
}

TEST(FirmwareMailboxSmCheck, OddStartIsRejected) {
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[0].start = 0x1001;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm0OddStart);
  sms = good_layout();
  sms[1].start = 0x1201;
  EXPECT_EQ(check(sms, product("ds5c1").mailbox_rules), MailboxSmFault::Sm1OddStart);  // E-811: both (L7125)
}

// A6B Err81.1 names an odd address of the receive mailbox only (L33414): SM1's start is not checked.
TEST(FirmwareMailboxSmCheck, A6bChecksOnlyTheReceiveMailboxForAnOddStart) {
  const auto rules = product("a6b").mailbox_rules;
  EXPECT_FALSE(rules.require_even_sm1_start);
  auto sms = good_layout();
  sms[1].start = 0x1201;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, A6bControlLowNibbleMustBeMailboxWriteAndRead) {
  // 0804h bits 3-0 = 0110b, 080Ch bits 3-0 = 0010b; upper bits (IRQ enables) are free.
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[0].control = 0x06;  // no PDI IRQ bit: still a valid write mailbox for the A6B
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
  sms[0].control = 0x22;  // read mailbox in SM0
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm0Control);
  sms = good_layout();
  sms[1].control = 0x26;  // write mailbox in SM1
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Control);
  sms[1].control = 0x20;  // 3-buffer instead of mailbox
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Control);
}

TEST(FirmwareMailboxSmCheck, Ds5c1ControlBits5to0AreChecked) {
  const auto rules = product("ds5c1").mailbox_rules;
  auto sms = good_layout();
  sms[0].control = 0x06;  // bit5 (AL event enable) missing: E-811 checks bits 5-0 (L7125)
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm0Control);
  sms = good_layout();
  sms[1].control = 0x02;
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Sm1Control);
}

TEST(FirmwareMailboxSmCheck, Sm0AndSm1MustNotOverlap) {
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[1].start = 0x10FE;  // last two bytes of SM0
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Overlap);
  sms[1].start = 0x1100;  // adjacent is fine
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, EnabledProcessDataSmMustNotOverlapMailboxes) {
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[2].start = 0x1200;  // SM2 on top of SM1
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Overlap);
  sms[2].activate = 0;  // a disabled SM occupies nothing
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, BufferedSmOccupiesThreeBuffers) {
  // A 3-buffer SM of 0x40 bytes spans 0xC0 bytes: its third buffer can reach into SM0 even
  // though its first buffer ends well before it.
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[2] = sm(0x0F44, 0x40, 0x64, true);  // 3 x 0x40 = 0xC0 -> ends at 0x1004, inside SM0
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Overlap);
  sms[2] = sm(0x0F40, 0x40, 0x64, true);  // ends exactly at 0x1000
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
  sms[2] = sm(0x0F44, 0x40, 0x66, true);  // same start in mailbox mode: one buffer, no overlap
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, ZeroLengthProcessDataSmOverlapsNothing) {
  const auto rules = product("a6b").mailbox_rules;
  auto sms = good_layout();
  sms[3] = sm(0x1000, 0, 0x20, true);
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, AddressSpaceEndDoesNotWrap) {
  profile::MailboxSmRules rules = product("a6b").mailbox_rules;
  rules.sm0_start_max = 0xFFFF;
  rules.sm1_start_max = 0xFFFF;
  auto sms = good_layout();
  sms[0] = sm(0xFF00, 0x200, 0x26, true);  // runs past 0xFFFF: must not wrap onto SM1 at 0x1200
  EXPECT_EQ(check(sms, rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, BootRulesCapLengthsAtTheBootMailboxSize) {
  const profile::ProductProfile& ds1000a = product("ds1000a");  // boot mailboxes 128 bytes
  const auto boot = boot_mailbox_rules(ds1000a);
  EXPECT_EQ(boot.sm0_max_length, 128);
  EXPECT_EQ(boot.sm1_max_length, 128);
  EXPECT_EQ(boot.sm0_min_length, ds1000a.mailbox_rules.sm0_min_length);
  std::array<SmChannel, 4> sms = {sm(0x1000, 128, 0x26, true), sm(0x1080, 128, 0x22, true),
                                  sm(0x1100, 0, 0x64, false), sm(0x1180, 0, 0x20, false)};
  EXPECT_EQ(check(sms, boot), MailboxSmFault::Ok);
  sms[1].length = 130;
  EXPECT_EQ(check(sms, boot), MailboxSmFault::Sm1Length);
}

TEST(FirmwareMailboxSmCheck, BootRulesWithoutBootMailboxAreTheStandardRules) {
  const auto boot = boot_mailbox_rules(product("ds5c1"));
  EXPECT_EQ(boot.sm0_max_length, 256);
  EXPECT_EQ(boot.sm1_min_length, 40);
}

TEST(FirmwareMailboxSmCheck, FewerThanTwoSmsIsNeverValid) {
  const std::array<SmChannel, 1> one = {sm(0x1000, 256, 0x26, true)};
  EXPECT_NE(check_mailbox_sms(one, product("a6b").mailbox_rules), MailboxSmFault::Ok);
}

TEST(FirmwareMailboxSmCheck, EveryFaultHasADescription) {
  for (int f = 0; f <= static_cast<int>(MailboxSmFault::Overlap); ++f)
    EXPECT_NE(describe(static_cast<MailboxSmFault>(f)), "?");
}

}  // namespace
}  // namespace vdrive::firmware
