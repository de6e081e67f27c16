// A recovering master's record of one drive's outages (master/drive_recovery.hpp): when an outage
// starts and ends, which 603Fh code it had, and when it is overdue, fed as the cyclic task would.
#include <gtest/gtest.h>

#include <vector>

#include "master/drive_recovery.hpp"

namespace vdrive::master {
namespace {

constexpr Nanos kMs = 1'000'000;
using Event = DriveRecovery::Event;

TEST(DriveRecovery, ADriveNeverEnabledHasNoOutage) {
  DriveRecovery r(100 * kMs);
  for (Nanos t = 0; t < 1000 * kMs; t += kMs) EXPECT_EQ(r.update(t, false, 0xFF10), Event::none);
  EXPECT_EQ(r.outages(), 0u);
  EXPECT_FALSE(r.out());
}

TEST(DriveRecovery, AFaultIsAnOutageUntilEnabledAgainWithItsCode) {
  DriveRecovery r(1000 * kMs);
  EXPECT_EQ(r.update(0, true, 0), Event::none);
  EXPECT_EQ(r.update(1 * kMs, false, 0), Event::lost);  // the status word drops first
  EXPECT_TRUE(r.out());
  EXPECT_EQ(r.update(2 * kMs, false, 0xFF18), Event::none);  // 603Fh a cycle later
  EXPECT_EQ(r.code(), 0xFF18);
  EXPECT_EQ(r.update(3 * kMs, false, 0), Event::none);  // reset: 603Fh clears before the enable
  EXPECT_EQ(r.update(251 * kMs, true, 0), Event::recovered);
  EXPECT_FALSE(r.out());
  EXPECT_EQ(r.outages(), 1u);
  EXPECT_EQ(r.recoveries(), 1u);
  EXPECT_EQ(r.overdue(), 0u);
  EXPECT_EQ(r.last_duration(), 250 * kMs);
  EXPECT_EQ(r.longest(), 250 * kMs);
  ASSERT_EQ(r.codes().size(), 1u);
  EXPECT_EQ(r.codes()[0].code, 0xFF18);
  EXPECT_EQ(r.codes()[0].count, 1u);
}

TEST(DriveRecovery, CodesAreCountedPerCodeAndADisableWithoutCodeAsNone) {
  DriveRecovery r(1000 * kMs);
  Nanos t = 0;
  auto outage = [&](std::uint16_t code, Nanos length) {
    r.update(t += kMs, true, 0);
    r.update(t += kMs, false, code);
    r.update(t += length, true, 0);
  };
  outage(0xFF18, 10 * kMs);
  outage(0xFF50, 30 * kMs);
  outage(0xFF18, 20 * kMs);
  outage(0, 5 * kMs);  // an AL error disabled it without an alarm
  EXPECT_EQ(r.outages(), 4u);
  EXPECT_EQ(r.recoveries(), 4u);
  EXPECT_EQ(r.longest(), 30 * kMs);
  std::vector<std::pair<std::uint16_t, std::uint64_t>> codes;
  for (const AlarmCount& a : r.codes()) codes.emplace_back(a.code, a.count);
  EXPECT_EQ(codes, (std::vector<std::pair<std::uint16_t, std::uint64_t>>{{0xFF18, 2}, {0xFF50, 1}, {0, 1}}));
}

TEST(DriveRecovery, AnOutageBeyondTheBoundIsOverdueOnceEvenIfTheDriveComesBackLater) {
  DriveRecovery r(100 * kMs);
  r.update(0, true, 0);
  EXPECT_EQ(r.update(kMs, false, 0xFF10), Event::lost);
  Event last = Event::none;
  std::size_t overdue_events = 0;
  for (Nanos t = 2 * kMs; t <= 300 * kMs; t += kMs) {
    last = r.update(t, false, 0xFF10);
    if (last == Event::overdue) ++overdue_events;
  }
  EXPECT_EQ(overdue_events, 1u);
  EXPECT_EQ(r.overdue(), 1u);
  EXPECT_EQ(r.update(301 * kMs, true, 0), Event::recovered);
  EXPECT_EQ(r.overdue(), 1u) << "it came back, but too late";
  ASSERT_EQ(r.codes().size(), 1u);
  EXPECT_EQ(r.codes()[0].count, 1u) << "counted once, not again at the recovery";
}

TEST(DriveRecovery, MoreCodesThanTheTableHoldsAreCountedAsOthers) {
  DriveRecovery r(1000 * kMs);
  Nanos t = 0;
  for (std::uint16_t code = 1; code <= 10; ++code) {
    r.update(t += kMs, true, 0);
    r.update(t += kMs, false, code);
    r.update(t += kMs, true, 0);
  }
  EXPECT_EQ(r.codes().size(), 8u);
  EXPECT_EQ(r.other_codes(), 2u);
  EXPECT_EQ(r.recoveries(), 10u);
}

}  // namespace
}  // namespace vdrive::master
