// Xinje DS5C1 and DS1000A-EC alarms: 603Fh, 1001h, emergency, clearing, history, each against
// its manual (xinje-ds5c1-user-manual.zh.md, ds1000a-ec-manual.ja.txt).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "vdrive/drive/alarms/alarm_manager.hpp"
#include "vdrive/drive/alarms/xinje_alarm_history.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive {
namespace {

using ecat::coe::Emergency;

struct Bench {
  explicit Bench(std::string_view id)
      : profile(profile::load_profile(id)), dict(od::shared_dictionary(profile)), store(*dict),
        ctx{profile, store, units}, alarms(ctx, [this](const Emergency& e) { emcy.push_back(e); }) {
    alarms.power_on();
  }
  const profile::AlarmSpec& alarm(const char* code) {
    const profile::AlarmSpec* a = alarms.find(code);
    EXPECT_NE(a, nullptr) << code;
    return *a;
  }
  std::uint32_t read_uint(std::uint16_t index, std::uint8_t sub) {
    std::array<std::uint8_t, 8> buf{};
    std::size_t n = 0;
    EXPECT_EQ(store.read(index, sub, buf, n, ecat::AlState::PreOp), od::SdoAbort::Ok);
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < n && i < 4; ++i) v |= std::uint32_t{buf[i]} << (8 * i);
    return v;
  }

  profile::ProductProfile profile;
  std::shared_ptr<const od::Dictionary> dict;
  od::ObjectStore store;
  UnitScaling units;
  DriveContext ctx;
  std::vector<Emergency> emcy;
  AlarmManager alarms;
};

bool same(const Emergency& e, std::uint16_t code, std::uint8_t reg) {
  return e.error_code == code && e.error_register == reg && e.data == std::array<std::uint8_t, 5>{};
}

// ---- DS5C1 ----------------------------------------------------------------------------------------

TEST(AlarmDs5c1, PositionDeviationE100ShowsFf0Ah) {
  Bench b("ds5c1");
  b.alarms.raise(b.alarm("E-100"), 0);
  // FF00h + main number 10 (E-100 -> 0Ah, L7371-L7378); 1001h bit 7: not an AL-coded alarm (L2579-L2581).
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF0Au);
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x80u);
  ASSERT_EQ(b.emcy.size(), 1u);
  EXPECT_TRUE(same(b.emcy[0], 0xFF0A, 0x80));   // no data bytes documented: zero
  EXPECT_FALSE(b.alarms.is_communication(b.alarm("E-100")));
}

TEST(AlarmDs5c1, PdoWatchdogE804NeedsTheAlAcknowledgeBeforeFaultReset) {
  Bench b("ds5c1");
  const auto& wd = b.alarm("E-804");
  b.alarms.raise(wd, 0);
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF50u);   // E-804 -> 80 = 50h
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x10u);     // E-800~7: AL-coded (L2576, L2580)
  EXPECT_TRUE(b.alarms.is_communication(wd));
  // Method 1: AL Control bit 4, then 6040h bit 7 0->1 (L7394-L7398).
  EXPECT_FALSE(b.alarms.reset(/*al_error_pending=*/true, 1));
  EXPECT_TRUE(b.alarms.active());
  EXPECT_TRUE(b.alarms.reset(false, 2));
  EXPECT_EQ(b.read_uint(0x603F, 0), 0u);
  ASSERT_EQ(b.emcy.size(), 2u);
  EXPECT_TRUE(same(b.emcy[1], 0, 0));
}

TEST(AlarmDs5c1, PanelOrSdo4000hClearNeedsNoAlAcknowledge) {
  Bench b("ds5c1");
  b.alarms.raise(b.alarm("E-804"), 0);
  // Methods 2 and 4 (F0-00 = 1, SDO 4000h = 1, L7400-L7412) name no AL acknowledge.
  EXPECT_FALSE(b.alarms.clear_from_drive(/*fault_reaction_active=*/true, 1));
  EXPECT_TRUE(b.alarms.clear_from_drive(false, 1));
  EXPECT_FALSE(b.alarms.active());
}

// 603Fh for a general alarm (issue 22 item 10). The manual: "显示伺服驱动器正在发生的报警主编号（3791及以上
// 版本，通用报警显示完整错误代码，总线类报警显示主编号）" (L2557, also L7378, L9345-L9346) but bits 8-15 are
// "值固定为FFh" (L9353) and bits 0-7 "显示正在发生的报警主编号", with "16h=22d, 当前报警可能为E-220~E-229中的一个"
// (L9352), and every example keeps the main number (E-030 -> FF03h under the 3791 sentence itself, L2557,
// L7378). A full code does not fit bits 0-7 for E-260..E-320, and FF00h + full code would make FF1Ah
// both E-026 and E-26x: 603Fh keeps FF00h + main number; the full code is U1-00 = 3100h, which the
// manual names for reading the current alarm by SDO (L7380-L7384).
TEST(AlarmDs5c1, GeneralAlarm603FhShowsTheMainNumberAndU100TheFullCode) {
  Bench b("ds5c1");
  b.alarms.raise(b.alarm("E-222"), 0);
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF16u);   // 16h = 22d (L9352)
  EXPECT_EQ(b.read_uint(0x3100, 0), 222u);      // U1-00 current alarm code (L7380, L9072)
  b.alarms.raise(b.alarm("E-320"), 1);
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF20u);   // newest alarm, main number 32
  EXPECT_EQ(b.read_uint(0x3100, 0), 320u);
  EXPECT_EQ(b.read_uint(0x3101, 0), 0u);        // U1-01 current warning code (L9073): none
  EXPECT_TRUE(b.alarms.clear_from_drive(false, 2));
  EXPECT_EQ(b.read_uint(0x603F, 0), 0u);
  EXPECT_EQ(b.read_uint(0x3100, 0), 0u);
}

TEST(AlarmDs5c1, BusAlarm603FhShowsTheMainNumberE817A000h) {
  Bench b("ds5c1");
  b.alarms.raise(b.alarm("E-851"), 0);
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF55u);   // "总线类报警显示主编号" (L2557): 55h = 85d
  EXPECT_EQ(b.read_uint(0x3100, 0), 851u);
  b.alarms.power_on();
  b.alarms.raise(b.alarm("E-817"), 0);
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xA000u);   // the exception (L9355)
  EXPECT_EQ(b.read_uint(0x3100, 0), 817u);
}

TEST(AlarmDs5c1, E899BusPeripheralFailureNeedsPowerCycle) {
  Bench b("ds5c1");
  b.alarms.raise(b.alarm("E-899"), 0);   // "contact the dealer" (L7139): not clearable
  EXPECT_FALSE(b.alarms.reset(false, 1));
  EXPECT_TRUE(b.alarms.active());
  b.alarms.power_on();
  EXPECT_FALSE(b.alarms.active());
}

TEST(AlarmDs5c1, HistoryKeepsTheHistoryColumnsAlarmsOnly) {
  Bench b("ds5c1");
  b.alarms.raise(b.alarm("E-100"), 0);
  b.alarms.reset(false, 1);
  b.alarms.raise(b.alarm("E-021"), 2);   // parameter out of range: history ○ (L7163)
  b.alarms.reset(false, 3);
  b.alarms.raise(b.alarm("E-080"), 4);   // overspeed: history √ (L7182)
  const auto* h = dynamic_cast<const XinjeAlarmHistory*>(b.alarms.history());
  ASSERT_NE(h, nullptr);
  ASSERT_EQ(h->log().size(), 2u);
  EXPECT_EQ(h->log().newest(0)->code, "E-080");
  EXPECT_EQ(h->log().newest(1)->code, "E-100");
  EXPECT_EQ(h->log().total(), 2u);       // U1-14 (L9086)
  EXPECT_EQ(h->since_power_on(), 2u);    // U1-12 (L9084)
  b.alarms.power_on();
  EXPECT_EQ(h->log().size(), 2u);        // history kept over a power cycle
  EXPECT_EQ(h->since_power_on(), 0u);
}

// ---- DS1000A-EC ------------------------------------------------------------------------------------

TEST(AlarmDs1000a, FullCountFf02hUsesTheGenericErrorRegister) {
  Bench b("ds1000a");
  b.alarms.raise(b.alarm("FF02h"), 0);
  EXPECT_EQ(b.read_uint(0x603F, 0), 0xFF02u);   // the code is the 603Fh value (L4313-L4336)
  // 1001h has no documented bits (L4433): CiA 301, generic + manufacturer specific.
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x81u);
  ASSERT_EQ(b.emcy.size(), 1u);
  EXPECT_TRUE(same(b.emcy[0], 0xFF02, 0x81));
  EXPECT_EQ(b.alarms.history(), nullptr);   // no alarm history (L4309-L4392)
  EXPECT_TRUE(b.alarms.reset(/*al_error_pending=*/true, 1));   // no AL-coded alarm: fault reset alone
  ASSERT_EQ(b.emcy.size(), 2u);
  EXPECT_TRUE(same(b.emcy[1], 0, 0));
}

TEST(AlarmDs1000a, CiA301ClassesOfTheOtherCodes) {
  Bench b("ds1000a");
  b.alarms.raise(b.alarm("7500h"), 0);   // CiA 402 7500h "communication": bit 4
  EXPECT_EQ(b.read_uint(0x1001, 0), 0x11u);
  Bench c("ds1000a");
  c.alarms.raise(c.alarm("8312h"), 0);   // monitoring class: generic only
  EXPECT_EQ(c.read_uint(0x1001, 0), 0x01u);
}

TEST(AlarmDs1000a, EepromErrorIsRepairOnlyAndEsmErrorIsTheCommunicationAlarm) {
  Bench b("ds1000a");
  b.alarms.raise(b.alarm("5530h"), 0);   // "repair" (L4318)
  EXPECT_FALSE(b.alarms.reset(false, 1));
  EXPECT_EQ(b.read_uint(0x603F, 0), 0x5530u);
  b.alarms.power_on();
  EXPECT_EQ(b.read_uint(0x603F, 0), 0u);
  EXPECT_TRUE(b.alarms.is_communication(b.alarm("FF80h")));   // L4386-L4392
  EXPECT_FALSE(b.alarms.is_communication(b.alarm("7500h")));  // internal, not EtherCAT
}

}  // namespace
}  // namespace vdrive::drive
