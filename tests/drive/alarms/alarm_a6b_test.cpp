// Panasonic MINAS-A6B alarms: 603Fh, 1001h, emergency bytes, clearing procedure and the 10F3h
// diagnosis history, each checked against the manual (panasonic-minas-a6b-ethercat-spec.zh.txt).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "vdrive/drive/alarms/alarm_manager.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive {
namespace {

using ecat::coe::Emergency;
constexpr Nanos kSecond = 1'000'000'000;

struct A6bBench {
  A6bBench()
      : profile(profile::load_profile("a6b")), dict(od::shared_dictionary(profile)), store(*dict),
        ctx{profile, store, units}, alarms(ctx, [this](const Emergency& e) { emcy.push_back(e); }) {
    alarms.power_on();
  }
  const profile::AlarmSpec& alarm(const char* code) {
    const profile::AlarmSpec* a = alarms.find(code);
    EXPECT_NE(a, nullptr) << code;
    return *a;
  }
  std::vector<std::uint8_t> sdo_read(std::uint16_t index, std::uint8_t sub) {
    std::array<std::uint8_t, 64> buf{};
    std::size_t n = 0;
    EXPECT_EQ(store.read(index, sub, buf, n, ecat::AlState::PreOp), od::SdoAbort::Ok);
    return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
  }
  std::uint32_t read_uint(std::uint16_t index, std::uint8_t sub) {
    std::uint32_t v = 0;
    const auto bytes = sdo_read(index, sub);
    for (std::size_t i = 0; i < bytes.size() && i < 4; ++i) v |= std::uint32_t{bytes[i]} << (8 * i);
    return v;
  }
  od::SdoAbort sdo_write_u8(std::uint16_t index, std::uint8_t sub, std::uint8_t v) {
    const std::array<std::uint8_t, 1> b{v};
    return store.write(index, sub, b, ecat::AlState::PreOp);
  }

  profile::ProductProfile profile;
  std::shared_ptr<const od::Dictionary> dict;
  od::ObjectStore store;
  UnitScaling units;
  DriveContext ctx;
  std::vector<Emergency> emcy;
  AlarmManager alarms;
};

bool same(const Emergency& e, std::uint16_t code, std::uint8_t reg, std::array<std::uint8_t, 5> data) {
  return e.error_code == code && e.error_register == reg && e.data == data;
}

TEST(AlarmA6b, PositionDeviationShowsFf18hAndSendsItsEmergency) {
  A6bBench b;
  EXPECT_FALSE(b.alarms.active());
  EXPECT_EQ(b.read_uint(0x603F, 0), 0u);
  ASSERT_TRUE(b.alarms.raise(b.alarm("24.0"), kSecond));
  EXPECT_TRUE(b.alarms.active());
  // 603Fh = FF00h + main number 24 = 18h (L33980-L33992); 1001h bit 7: no AL status code (L4784-L4794).
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF18u);
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x80u);
  ASSERT_EQ(b.emcy.size(), 1u);
  EXPECT_TRUE(same(b.emcy[0], 0xFF18, 0x80, {0, 0, 0, 0, 0}));
  EXPECT_FALSE(b.alarms.raise(b.alarm("24.0"), 2 * kSecond));   // already active: no second emergency
  EXPECT_EQ(b.emcy.size(), 1u);
}

TEST(AlarmA6b, EmergencyCarriesTheSubCodeAsTheManualsErr16_1Example) {
  A6bBench b;
  b.alarms.raise(b.alarm("16.1"), 0);
  ASSERT_EQ(b.emcy.size(), 1u);
  // "FF10h 80h 01h 00h 00h 00h 00h" (L4840).
  EXPECT_TRUE(same(b.emcy[0], 0xFF10, 0x80, {0x01, 0, 0, 0, 0}));
  std::array<std::uint8_t, 10> wire{};
  b.emcy[0].encode(wire);
  EXPECT_EQ(wire, (std::array<std::uint8_t, 10>{0x00, 0x10, 0x10, 0xFF, 0x80, 0x01, 0, 0, 0, 0}));
}

TEST(AlarmA6b, AlStatusCodeAlarmsSetErrorRegisterBit4AndErr81_7SendsA000h) {
  A6bBench b;
  b.alarms.raise(b.alarm("80.4"), 0);   // PDO watchdog, AL 001Bh (L32604)
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF50u);
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x10u);   // L4778, L4788-L4790
  ASSERT_EQ(b.emcy.size(), 1u);
  EXPECT_TRUE(same(b.emcy[0], 0xFF50, 0x10, {0x04, 0, 0, 0, 0}));

  A6bBench c;
  // Err81.7 case 2: SM2 start address wrong: A000h 10h 09h 00h 10h FEh 2Fh (L4952).
  c.alarms.raise(c.alarm("81.7"), 0, {0x09, 0x00, 0x10, 0xFE, 0x2F});
  EXPECT_EQ(c.read_uint(0x603F, 0), 0xA000u);   // L33996
  ASSERT_EQ(c.emcy.size(), 1u);
  EXPECT_TRUE(same(c.emcy[0], 0xA000, 0x10, {0x09, 0x00, 0x10, 0xFE, 0x2F}));
}

TEST(AlarmA6b, ErrorRegisterShowsEveryKindPresentAnd603FhTheNewest) {
  A6bBench b;
  b.alarms.raise(b.alarm("80.4"), 0);
  b.alarms.raise(b.alarm("26.0"), 1);
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF1Au);   // Err26 -> 1Ah, the newest emergency's code (L33998)
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x90u);
  ASSERT_EQ(b.emcy.size(), 2u);
  EXPECT_TRUE(same(b.emcy[1], 0xFF1A, 0x90, {0, 0, 0, 0, 0}));
  EXPECT_EQ(b.alarms.newest(), &b.alarm("26.0"));
}

TEST(AlarmA6b, AlCodedAlarmClearsOnlyAfterTheAlErrorIsAcknowledged) {
  A6bBench b;
  b.alarms.raise(b.alarm("80.4"), 0);
  // Method 1: AL Control bit 4 first, then 6040h bit 7 0->1 (L34013-L34017).
  EXPECT_FALSE(b.alarms.reset_allowed(/*al_error_pending=*/true, false, kSecond));
  EXPECT_FALSE(b.alarms.reset(true, kSecond));
  EXPECT_TRUE(b.alarms.active());
  EXPECT_EQ(b.emcy.size(), 1u);
  EXPECT_TRUE(b.alarms.reset_allowed(false, false, kSecond));
  EXPECT_TRUE(b.alarms.reset(false, kSecond));
  EXPECT_FALSE(b.alarms.active());
  EXPECT_EQ(b.read_uint(0x603F, 0), 0u);
  EXPECT_EQ(b.read_uint(0x1001, 0), 0u);
  ASSERT_EQ(b.emcy.size(), 2u);
  EXPECT_TRUE(same(b.emcy[1], 0x0000, 0x00, {0, 0, 0, 0, 0}));   // L4848-L4885
}

TEST(AlarmA6b, AlarmWithoutAlCodeIgnoresThePendingAlError) {
  A6bBench b;
  b.alarms.raise(b.alarm("88.2"), 0);   // ESM request during operation: AL code 0000h (L32641)
  EXPECT_TRUE(b.alarms.is_communication(b.alarm("88.2")));
  EXPECT_TRUE(b.alarms.reset(/*al_error_pending=*/true, kSecond));
  EXPECT_FALSE(b.alarms.active());
}

TEST(AlarmA6b, NoClearWhileTheCauseIsPresentOrFaultReactionIsActive) {
  A6bBench b;
  const auto& dev = b.alarm("24.0");
  b.alarms.raise(dev, 0);
  b.alarms.set_cause(dev, true);
  EXPECT_FALSE(b.alarms.reset_allowed(false, false, kSecond));
  EXPECT_FALSE(b.alarms.reset(false, kSecond));
  EXPECT_TRUE(b.alarms.active());
  b.alarms.set_cause(dev, false);
  EXPECT_FALSE(b.alarms.reset_allowed(false, /*fault_reaction_active=*/true, kSecond));   // L34060
  EXPECT_TRUE(b.alarms.reset_allowed(false, false, kSecond));
  EXPECT_TRUE(b.alarms.reset(false, kSecond));
}

TEST(AlarmA6b, OneCausePresentKeepsEveryAlarm) {
  // "unless the causes of all alarms are removed, an alarm whose cause was removed may not clear" (L34048-L34050).
  A6bBench b;
  b.alarms.raise(b.alarm("24.0"), 0);
  b.alarms.raise(b.alarm("26.0"), 0);
  b.alarms.set_cause(b.alarm("26.0"), true);
  EXPECT_FALSE(b.alarms.reset(false, kSecond));
  EXPECT_TRUE(b.alarms.is_active(b.alarm("24.0")));
  EXPECT_TRUE(b.alarms.is_active(b.alarm("26.0")));
}

TEST(AlarmA6b, NonClearableAlarmNeedsAPowerCycle) {
  A6bBench b;
  b.alarms.raise(b.alarm("85.3"), 0);   // SII EEPROM error: clearable No (L32630)
  b.alarms.raise(b.alarm("24.0"), 1);
  EXPECT_FALSE(b.alarms.reset_allowed(false, false, kSecond));
  EXPECT_FALSE(b.alarms.reset(false, kSecond));
  // The clearable one went, the non-clearable one stays and is what 603Fh shows (L34044-L34046).
  EXPECT_FALSE(b.alarms.is_active(b.alarm("24.0")));
  EXPECT_TRUE(b.alarms.is_active(b.alarm("85.3")));
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF55u);
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x10u);
  EXPECT_EQ(b.emcy.size(), 2u);   // no "cleared" emergency while an alarm remains
  b.alarms.power_on();
  EXPECT_FALSE(b.alarms.active());
  EXPECT_EQ(b.read_uint(0x603F, 0), 0u);
}

TEST(AlarmA6b, OverloadErr16_0ClearsTenSecondsAfterItOccurred) {
  A6bBench b;
  const auto& overload = b.alarm("16.0");
  b.alarms.raise(overload, 1 * kSecond);
  EXPECT_FALSE(b.alarms.reset_allowed(false, false, 5 * kSecond));
  // A reset asked for early is accepted and carried out once the alarm may clear (L32918-L32920).
  EXPECT_FALSE(b.alarms.reset(false, 5 * kSecond));
  EXPECT_TRUE(b.alarms.reset_pending());
  EXPECT_TRUE(b.alarms.active());
  EXPECT_FALSE(b.alarms.complete_pending_reset(false, false, 11 * kSecond - 1));
  EXPECT_TRUE(b.alarms.active());
  EXPECT_TRUE(b.alarms.complete_pending_reset(false, false, 11 * kSecond));
  EXPECT_FALSE(b.alarms.active());
  EXPECT_FALSE(b.alarms.reset_pending());
  ASSERT_EQ(b.emcy.size(), 2u);
  EXPECT_TRUE(same(b.emcy[1], 0, 0, {0, 0, 0, 0, 0}));
  // Err16.1 (torque saturation) has no such delay.
  b.alarms.raise(b.alarm("16.1"), 20 * kSecond);
  EXPECT_TRUE(b.alarms.reset(false, 20 * kSecond + 1));
}

TEST(AlarmA6b, CommunicationAlarmsAreErr80_81_85_88) {
  A6bBench b;
  for (const char* code : {"80.0", "81.7", "85.2", "88.1"}) EXPECT_TRUE(b.alarms.is_communication(b.alarm(code))) << code;
  for (const char* code : {"84.3", "87.0", "24.0", "16.0"}) EXPECT_FALSE(b.alarms.is_communication(b.alarm(code))) << code;
}

TEST(AlarmA6b, DiagnosisHistoryFillsUpwardFrom06h) {
  A6bBench b;
  // Empty: 00h = 13h, 01h = 0Eh, 02h = 0, flags bits 0-2 and 5 (L9024-L9102).
  EXPECT_EQ(b.read_uint(0x10F3, 0x00), 0x13u);
  EXPECT_EQ(b.read_uint(0x10F3, 0x01), 0x0Eu);
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0u);
  EXPECT_EQ(b.read_uint(0x10F3, 0x05), 0x0027u);

  b.alarms.raise(b.alarm("24.0"), 0);
  b.alarms.reset(false, 1);
  b.alarms.raise(b.alarm("16.1"), 2);
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0x07u);
  EXPECT_EQ(b.read_uint(0x10F3, 0x05), 0x0007u);   // bit 5 clear: history present
  // Diag code (603Fh << 16 | E800h), flags 0002h, text ID main/sub, time stamp 0 (L9106-L9134).
  EXPECT_EQ(b.sdo_read(0x10F3, 0x06),
            (std::vector<std::uint8_t>{0x00, 0xE8, 0x18, 0xFF, 0x02, 0x00, 0x00, 0x18, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(b.sdo_read(0x10F3, 0x07),
            (std::vector<std::uint8_t>{0x00, 0xE8, 0x10, 0xFF, 0x02, 0x00, 0x01, 0x10, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(b.sdo_read(0x10F3, 0x08), std::vector<std::uint8_t>(16, 0));
}

TEST(AlarmA6b, AlarmsWithoutHistoryAreNotRecorded) {
  A6bBench b;
  b.alarms.raise(b.alarm("13.0"), 0);   // main power undervoltage: history No (L32682)
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0u);
  EXPECT_EQ(b.alarms.history()->log().size(), 0u);
  EXPECT_EQ(b.emcy.size(), 1u);         // the emergency is still sent
}

TEST(AlarmA6b, HistoryKeepsTheLast14AndSurvivesPowerOn) {
  A6bBench b;
  const char* codes[] = {"24.0", "26.0", "16.1"};
  for (int i = 0; i < 15; ++i) {
    b.alarms.raise(b.alarm(codes[i % 3]), i);
    b.alarms.reset(false, i);
  }
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0x13u);   // full: newest at 13h (L8952-L8982)
  // 15 alarms: the first (24.0) was dropped; 06h holds the 2nd (26.0), 13h the 15th (16.1).
  EXPECT_EQ(b.sdo_read(0x10F3, 0x06)[3], 0xFF);
  EXPECT_EQ(b.sdo_read(0x10F3, 0x06)[2], 0x1A);
  EXPECT_EQ(b.sdo_read(0x10F3, 0x13)[2], 0x10);
  b.store.reset_to_defaults();   // control power off: RAM lost, history read back from EEPROM (L8929-L8931)
  b.alarms.power_on();
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0x13u);
  EXPECT_EQ(b.sdo_read(0x10F3, 0x13)[2], 0x10);
  EXPECT_EQ(b.read_uint(0x10F3, 0x05), 0x0007u);
}

TEST(AlarmA6b, Writing00hTo10F3h03hClearsTheHistoryAndOtherValuesAbort) {
  A6bBench b;
  b.alarms.raise(b.alarm("24.0"), 0);
  EXPECT_EQ(b.sdo_write_u8(0x10F3, 0x03, 0x01), od::SdoAbort::ValueRangeExceeded);   // 06090030h (L9058-L9060)
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0x06u);
  EXPECT_EQ(b.sdo_write_u8(0x10F3, 0x03, 0x00), od::SdoAbort::Ok);
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0u);
  EXPECT_EQ(b.sdo_read(0x10F3, 0x06), std::vector<std::uint8_t>(16, 0));
  EXPECT_EQ(b.read_uint(0x10F3, 0x05), 0x0027u);   // bit 5: cleared (L9094-L9100)
  EXPECT_EQ(b.read_uint(0x10F3, 0x03), 0u);
  // Cleared stays cleared over a power cycle: the EEPROM copy is gone too.
  b.alarms.power_on();
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0u);
}

TEST(AlarmA6b, EmergencyOffWhen10F3h05hBit0IsZero) {
  A6bBench b;
  const std::array<std::uint8_t, 2> flags{0x06, 0x00};
  ASSERT_EQ(b.store.write(0x10F3, 0x05, flags, ecat::AlState::PreOp), od::SdoAbort::Ok);
  b.alarms.raise(b.alarm("24.0"), 0);
  EXPECT_TRUE(b.emcy.empty());              // L4573-L4575, L9076-L9080
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF18u);
  EXPECT_EQ(b.read_uint(0x10F3, 0x02), 0x06u);   // the history is still kept
  b.alarms.reset(false, 1);
  EXPECT_TRUE(b.emcy.empty());
}

TEST(AlarmA6b, AnAlarmOfAnotherTableIsRefused) {
  A6bBench b;
  profile::AlarmSpec stranger;
  stranger.code = "24.0";
  stranger.error_code = 0xFF18;
  EXPECT_FALSE(b.alarms.raise(stranger, 0));
  EXPECT_FALSE(b.alarms.active());
  EXPECT_EQ(b.alarms.find("99.9"), nullptr);
}

}  // namespace
}  // namespace vdrive::drive
