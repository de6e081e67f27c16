// The pure PDO checks: SM2/SM3 against the mapped size (A6B Err81.7 L33546-L33624, DS5C1 E-817
// L7129-L7133), the process-data watchdog setting (A6B Err81.4 L33447-L33481), the mapping-entry
// format (index << 16 | subindex << 8 | bits, A6B L7064-L7077) and the product limits.
#include <gtest/gtest.h>

#include <array>

#include "vdrive/firmware/pdo/pdo_limits.hpp"
#include "vdrive/firmware/pdo/pdo_mapping.hpp"
#include "vdrive/firmware/pdo/process_data_sm_check.hpp"
#include "vdrive/firmware/pdo/watchdog_setting_check.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::firmware::pdo {
namespace {

constexpr std::uint32_t kRamEnd = 0x3000;  // 8 KiB process RAM (A6B L3378-L3380)

SmChannel channel(std::uint16_t start, std::uint16_t length, std::uint8_t control, bool enable) {
  SmChannel c;
  c.start = start;
  c.length = length;
  c.control = control;
  c.activate = enable ? 1 : 0;
  return c;
}

// A6B's layout: mailboxes 1000h/1200h (256 B), SM2 1400h (9 B), SM3 1600h (23 B).
std::array<SmChannel, 4> good_layout() {
  return {channel(0x1000, 0x100, 0x26, true), channel(0x1200, 0x100, 0x22, true),
          channel(0x1400, 9, 0x64, true), channel(0x1600, 23, 0x20, true)};
}

TEST(PdoSmCheck, ProductLayoutPasses) {
  const auto sms = good_layout();
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Ok);
  EXPECT_EQ(check_process_data_sm(sms, 3, 23, kRamEnd), PdSmFault::Ok);
}

TEST(PdoSmCheck, LengthMustEqualMappedSize) {
  const auto sms = good_layout();
  EXPECT_EQ(check_process_data_sm(sms, 2, 10, kRamEnd), PdSmFault::Length);
  EXPECT_EQ(check_process_data_sm(sms, 3, 22, kRamEnd), PdSmFault::Length);
}

TEST(PdoSmCheck, EnabledIffDataIsMapped) {
  auto sms = good_layout();
  sms[2].activate = 0;
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Disabled);
  EXPECT_EQ(check_process_data_sm(sms, 2, 0, kRamEnd), PdSmFault::Ok);
  // Nothing mapped and SM2 running with 9 bytes: the manuals' length rule (length != RxPDO size,
  // A6B L33564-L33566, DS5C1 L7129-L7133), not a rule of its own.
  EXPECT_EQ(check_process_data_sm(good_layout(), 2, 0, kRamEnd), PdSmFault::Length);
}

// An enabled SM2 of length 0 with nothing mapped: the ESC does not run it, so only a product whose
// firmware wants unused SMs disabled refuses it (ETG SSC; A6B L4907, L4974); the DS5C1's E-817
// list has nothing against it (L7129-L7133).
TEST(PdoSmCheck, EnabledEmptySmWithNothingMappedOnlyWhereTheProductWantsItDisabled) {
  auto sms = good_layout();
  sms[2].length = 0;
  EXPECT_EQ(check_process_data_sm(sms, 2, true, 0, kRamEnd, true, /*unused_must_be_disabled=*/false), PdSmFault::Ok);
  EXPECT_EQ(check_process_data_sm(sms, 2, true, 0, kRamEnd, true, /*unused_must_be_disabled=*/true),
            PdSmFault::EnabledWithoutData);
  sms[2].activate = 0;
  EXPECT_EQ(check_process_data_sm(sms, 2, true, 0, kRamEnd, true, /*unused_must_be_disabled=*/true), PdSmFault::Ok);
  // A disabled SM is not in use: a length left in it is not looked at.
  sms[2].length = 9;
  EXPECT_EQ(check_process_data_sm(sms, 2, true, 0, kRamEnd, true, /*unused_must_be_disabled=*/true), PdSmFault::Ok);
}

TEST(PdoSmCheck, StartEvenAndThreeBuffersInsideProcessRam) {
  auto sms = good_layout();
  sms[2].start = 0x1401;
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::OddStart);
  sms[2].start = 0x0F00;  // registers, not process RAM
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Start);
  sms[2].start = 0x2FF0;  // 3 x 9 bytes end at 0x300B, past 0x2FFF
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Start);
  sms[2].start = 0x2FE4;  // 3 x 9 bytes end exactly at 0x3000
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Ok);
}

// A6B Err81.7 checks the direction bits 3-2 only (L33570, L33610): a mailbox-mode SM2 that the
// master writes passes when the mode is not checked; the direction still counts.
TEST(PdoSmCheck, WithoutTheModeCheckOnlyTheDirectionCounts) {
  auto sms = good_layout();
  sms[2].control = 0x66;  // mailbox mode, ECAT writes
  EXPECT_EQ(check_process_data_sm(sms, 2, true, 9, kRamEnd, /*check_mode=*/false), PdSmFault::Ok);
  EXPECT_EQ(check_process_data_sm(sms, 2, true, 9, kRamEnd, /*check_mode=*/true), PdSmFault::Control);
  sms[2].control = 0x60;  // 3-buffer, but ECAT reads
  EXPECT_EQ(check_process_data_sm(sms, 2, true, 9, kRamEnd, /*check_mode=*/false), PdSmFault::Control);
  EXPECT_FALSE(vdrive::profile::load_profile("a6b").pdo_rules.sm_control_mode_checked);
  EXPECT_TRUE(vdrive::profile::load_profile("ds5c1").pdo_rules.sm_control_mode_checked);
}

TEST(PdoSmCheck, ControlMustBeThreeBufferWithTheDirection) {
  auto sms = good_layout();
  sms[2].control = 0x66;  // mailbox mode
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Control);
  sms[2].control = 0x60;  // 3-buffer, but ECAT reads
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Control);
  sms[3].control = 0x24;  // inputs the master would write
  EXPECT_EQ(check_process_data_sm(sms, 3, 23, kRamEnd), PdSmFault::Control);
}

TEST(PdoSmCheck, BuffersMustNotOverlap) {
  auto sms = good_layout();
  sms[3].start = 0x1410;  // inside SM2's three buffers 1400h-141Ah
  EXPECT_EQ(check_process_data_sm(sms, 3, 23, kRamEnd), PdSmFault::Overlap);
  sms[3].start = 0x1600;
  sms[2].start = 0x10F0;  // into the SM0 mailbox 1000h-10FFh
  EXPECT_EQ(check_process_data_sm(sms, 2, 9, kRamEnd), PdSmFault::Overlap);
}

TEST(PdoWatchdogSetting, EscTimeFormula) {
  // Reset values: divider 09C2h (100 us tick), time 03E8h -> 100 ms.
  EXPECT_EQ(process_data_watchdog_time(0x09C2, 0x03E8), 100'000'000);
}

TEST(PdoWatchdogSetting, A6bNeedsTwoCyclesOrTwoMillisecondsInFreeRun) {
  const WatchdogLimits a6b{2, 2'000'000};
  WatchdogSetting s;
  s.enabled = true;
  s.synchronised = true;
  s.cycle_ns = 1'000'000;
  s.time = 1'999'999;
  EXPECT_FALSE(watchdog_setting_ok(s, a6b));
  s.time = 2'000'000;
  EXPECT_TRUE(watchdog_setting_ok(s, a6b));
  s.synchronised = false;
  s.time = 1'500'000;
  EXPECT_FALSE(watchdog_setting_ok(s, a6b));
  s.enabled = false;  // watchdog off: nothing to check
  EXPECT_TRUE(watchdog_setting_ok(s, a6b));
}

TEST(PdoMappingEntry, DecodesIndexSubindexBits) {
  const ecat::PdoMappingEntry e = ecat::PdoMappingEntry::decode(0x60FE0120);  // DS1000A 1600h 60FE:01 32 bit
  EXPECT_EQ(e.index, 0x60FE);
  EXPECT_EQ(e.subindex, 0x01);
  EXPECT_EQ(e.bits, 0x20);
  EXPECT_FALSE(e.is_gap());
  EXPECT_EQ(ecat::PdoMappingEntry::encode(0x6040, 0, 16), 0x60400010u);
  EXPECT_TRUE(ecat::PdoMappingEntry::decode(0x00000008).is_gap());
}

TEST(PdoLimits, ManualsLimits) {
  const PdoLimits a6b = limits_for(profile::load_profile("a6b"));
  EXPECT_EQ(a6b.rx.max_bytes, 32);           // L2861-L2865
  EXPECT_EQ(a6b.tx.max_assigned, 4);         // L6892-L7000
  EXPECT_EQ(a6b.rx.max_entries, 32);         // L7064-L7077
  EXPECT_EQ(a6b.wrong_state_abort, od::SdoAbort::SubindexCannotBeWritten);
  EXPECT_TRUE(a6b.writable_in(ecat::AlState::PreOp));
  EXPECT_FALSE(a6b.writable_in(ecat::AlState::SafeOp));
  const PdoLimits ds1000a = limits_for(profile::load_profile("ds1000a"));
  EXPECT_EQ(ds1000a.rx.max_assigned, 1);     // 1C12h range 0-1 (L4673-L4684)
  EXPECT_EQ(ds1000a.tx.max_entries, 10);     // L4455-L4475
  const PdoLimits ds5c1 = limits_for(profile::load_profile("ds5c1"));
  EXPECT_EQ(ds5c1.rx.max_entries, 24);       // L5597-L5602
}

// ESI devices number their PDOs with gaps (a 2-channel analog input terminal: 1A00h and 1A02h, one
// per channel, 1A01h/1A03h being alternatives): every PDO of the rules is a mapping object, and
// nothing below the first or above the last. (It once took 1A00h + the count: 1A02h was refused
// at PreOp->SafeOp with AL 0024h.)
TEST(PdoLimits, MappingObjectsWithGapsAreAllMappingObjects) {
  profile::ProductProfile p;
  p.pdo_rules.tx_objects = {{.index = 0x1A00}, {.index = 0x1A02}};
  const PdoLimits l = limits_for(p);
  EXPECT_TRUE(l.tx.is_mapping_object(0x1A00));
  EXPECT_TRUE(l.tx.is_mapping_object(0x1A02));
  EXPECT_FALSE(l.tx.is_mapping_object(0x19FF));
  EXPECT_FALSE(l.tx.is_mapping_object(0x1A03));
  // No RxPDOs: no mapping object in that direction.
  EXPECT_FALSE(l.rx.is_mapping_object(0x1600));
  EXPECT_FALSE(l.rx.is_mapping_object(0x15FF));
}

}  // namespace
}  // namespace vdrive::firmware::pdo
