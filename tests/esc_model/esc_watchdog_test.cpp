// Process-data and PDI watchdogs driven by a VirtualClock through tick()/next_deadline().
#include <gtest/gtest.h>

#include <cstdint>

#include "esc_model/watchdog.hpp"
#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

constexpr Nanos kMs = 1'000'000;
// Reset values: divider 0x09C2 -> (2498 + 2) * 40 ns = 100 us; time 1000 -> 100 ms.
constexpr Nanos kDefaultPeriod = 100 * kMs;
constexpr std::uint16_t kOut = 0x1100;

class WatchdogTest : public EscTest {
protected:
  void SetUp() override {
    set_station();
    // SM2: 3-buffer, ECAT writes, watchdog trigger.
    ASSERT_EQ(fpwr(0x0810, sm_regs(kOut, 2, 0x64)).wkc, 1);
  }
  void write_outputs() { ASSERT_EQ(fpwr(kOut, {1, 2}).wkc, 1); }
  void advance_to(Nanos t) {
    clock.set(t);
    esc->tick(t);
  }
};

TEST_F(WatchdogTest, NothingScheduledBeforeTheFirstTrigger) {
  EXPECT_EQ(esc->next_deadline(), INT64_MAX);
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0);
}

TEST_F(WatchdogTest, ProcessDataWatchdogExpiresWithoutWrites) {
  clock.set(5 * kMs);
  write_outputs();
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0x01);
  EXPECT_EQ(esc->next_deadline(), 5 * kMs + kDefaultPeriod);
  advance_to(5 * kMs + kDefaultPeriod - 1);
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0x01);
  EXPECT_EQ(peek32(0x0220) & 0x40u, 0u);
  advance_to(5 * kMs + kDefaultPeriod);
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0);
  EXPECT_EQ(esc->peek(0x0442), 1);
  EXPECT_EQ(peek32(0x0220) & 0x40u, 0x40u);
  EXPECT_EQ(esc->next_deadline(), INT64_MAX);  // stopped until triggered again
  // Reading the status from the PDI clears the event.
  EXPECT_EQ(pdi8(0x0440) & 0x01, 0);
  EXPECT_EQ(peek32(0x0220) & 0x40u, 0u);
}

TEST_F(WatchdogTest, EachCompletedWriteRestartsTheWatchdog) {
  write_outputs();
  for (int i = 1; i <= 5; ++i) {
    advance_to(i * 90 * kMs);
    write_outputs();
  }
  advance_to(5 * 90 * kMs + kDefaultPeriod - 1);
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0x01);
  EXPECT_EQ(esc->peek(0x0442), 0);
}

TEST_F(WatchdogTest, IncompleteWriteDoesNotTrigger) {
  write_outputs();
  advance_to(90 * kMs);
  EXPECT_EQ(fpwr(kOut, {1}).wkc, 1);  // first byte only
  advance_to(kDefaultPeriod);
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0);
}

TEST_F(WatchdogTest, PeriodFollowsDividerAndTime) {
  fpwr(0x0400, u16(0x0000));  // (0 + 2) * 40 ns = 80 ns per tick
  fpwr(0x0420, u16(10));
  write_outputs();
  EXPECT_EQ(esc->next_deadline(), 800);
  advance_to(800);
  EXPECT_EQ(esc->peek(0x0442), 1);
}

TEST_F(WatchdogTest, TimeZeroDisablesTheWatchdog) {
  fpwr(0x0420, u16(0));
  write_outputs();
  EXPECT_EQ(esc->next_deadline(), INT64_MAX);
  advance_to(10 * kDefaultPeriod);
  EXPECT_EQ(esc->peek(0x0442), 0);
}

TEST_F(WatchdogTest, CounterCountsExpiriesAndMasterWriteClearsIt) {
  for (int i = 0; i < 3; ++i) {
    write_outputs();
    advance_to(clock.now() + kDefaultPeriod);
  }
  EXPECT_EQ(fprd(0x0442, 1).data[0], 3);
  fpwr(0x0442, {0});
  EXPECT_EQ(esc->peek(0x0442), 0);
}

TEST_F(WatchdogTest, PdiWatchdogNeedsRegularPdiAccess) {
  EXPECT_EQ(peek16(0x0110) & 0x02, 0);
  pdi8(0x0130);
  EXPECT_EQ(peek16(0x0110) & 0x02, 0x02);
  EXPECT_EQ(esc->next_deadline(), kDefaultPeriod);
  advance_to(kDefaultPeriod);
  EXPECT_EQ(peek16(0x0110) & 0x02, 0);
  EXPECT_EQ(esc->peek(0x0443), 1);
}

TEST(WatchdogUnit, TriggerExpireOnce) {
  Watchdog w;
  w.configure(0x09C2, 0x03E8);
  EXPECT_EQ(w.period(), kDefaultPeriod);
  EXPECT_FALSE(w.expire_if_due(kDefaultPeriod * 2));  // not started
  w.trigger(10);
  EXPECT_FALSE(w.expire_if_due(9 + kDefaultPeriod));
  EXPECT_TRUE(w.expire_if_due(10 + kDefaultPeriod));
  EXPECT_FALSE(w.expire_if_due(20 + kDefaultPeriod));
}

}  // namespace
}  // namespace vdrive::esc::test
