// Transport: addressing of the typed calls, reply matching by index, timeout and bounded retries.
#include "master/transport.hpp"

#include <gtest/gtest.h>

#include "tests/master/scripted_link.hpp"

namespace vdrive::master {
namespace {

using test::ScriptedLink;

constexpr std::size_t kCmd = 16, kIdx = 17, kAdp = 18, kAdo = 20, kData = 26;

std::uint16_t le16(const std::vector<std::uint8_t>& f, std::size_t at) {
  return static_cast<std::uint16_t>(f[at] | (f[at + 1] << 8));
}
void set_wkc(std::vector<std::uint8_t>& f, std::uint16_t wkc) {
  const std::size_t len = le16(f, 22) & 0x7FF;
  f[kData + len] = static_cast<std::uint8_t>(wkc);
  f[kData + len + 1] = static_cast<std::uint8_t>(wkc >> 8);
}

TEST(Transport, AutoIncrementAddressIsMinusPosition) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto& f) { set_wkc(f, 1); return true; });
  Transport t(link, clock);
  std::array<std::uint8_t, 2> v{0x01, 0x10};
  EXPECT_EQ(t.apwr(2, 0x0010, v), 1);
  const auto& sent = link.sent.at(0);
  EXPECT_EQ(sent[kCmd], 2) << "APWR";
  EXPECT_EQ(le16(sent, kAdp), 0xFFFE);
  EXPECT_EQ(le16(sent, kAdo), 0x0010);
  EXPECT_EQ(sent[kData], 0x01);
  EXPECT_EQ(sent[kData + 1], 0x10);
}

TEST(Transport, ReadCopiesReplyDataAndTypedHelpersAreLittleEndian) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto& f) {
    f[kData] = 0x34;
    f[kData + 1] = 0x12;
    set_wkc(f, 1);
    return true;
  });
  Transport t(link, clock);
  EXPECT_EQ(t.fprd_value<std::uint16_t>(0x1001, 0x0130), 0x1234);
  EXPECT_EQ(link.sent.at(0)[kCmd], 4) << "FPRD";
  EXPECT_EQ(le16(link.sent.at(0), kAdp), 0x1001);
}

TEST(Transport, ValueReadsNeedWorkingCounterOne) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto&) { return true; });  // WKC stays 0: nobody answered
  Transport t(link, clock);
  EXPECT_EQ(t.fprd_value<std::uint16_t>(0x1009, 0x0130), std::nullopt);
  std::array<std::uint8_t, 2> d{};
  EXPECT_EQ(t.fprd(0x1009, 0x0130, d), 0) << "a reply with WKC 0 is a reply";
}

TEST(Transport, EachDatagramGetsTheNextIndex) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto& f) { set_wkc(f, 3); return true; });
  Transport t(link, clock);
  std::array<std::uint8_t, 2> d{};
  t.brd(0, d);
  t.brd(0, d);
  EXPECT_EQ(static_cast<std::uint8_t>(link.sent[1][kIdx] - link.sent[0][kIdx]), 1);
}

TEST(Transport, SkipsStaleRepliesAndMatchesOnIndex) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto& f) { set_wkc(f, 1); return true; });
  Transport t(link, clock);
  // A stale reply (different index) already waiting on the link must not be taken.
  std::array<std::uint8_t, 2> d{};
  t.brd(0, d);
  auto stale = link.sent.back();
  set_wkc(stale, 7);
  link.inject(stale);
  EXPECT_EQ(t.brd(0, d), 1);
}

TEST(Transport, RetriesThenGivesUp) {
  VirtualClock clock;
  int calls = 0;
  ScriptedLink link(clock, [&](auto&) { ++calls; return false; });
  TransportOptions opt;
  opt.retries = 2;
  opt.reply_timeout = 1'000'000;
  Transport t(link, clock, opt);
  std::array<std::uint8_t, 2> d{};
  EXPECT_EQ(t.brd(0, d), std::nullopt);
  EXPECT_EQ(calls, 3) << "first attempt + 2 retries";
  EXPECT_EQ(t.timeouts(), 3u);
  EXPECT_GE(clock.now(), 3 * opt.reply_timeout) << "each attempt waited its timeout";
}

TEST(Transport, RetrySucceedsAfterALostFrame) {
  VirtualClock clock;
  int calls = 0;
  ScriptedLink link(clock, [&](auto& f) {
    set_wkc(f, 2);
    return ++calls > 1;  // the first frame is lost on the wire
  });
  Transport t(link, clock);
  std::array<std::uint8_t, 2> d{};
  EXPECT_EQ(t.brd(0, d), 2);
  EXPECT_EQ(calls, 2);
}

TEST(Transport, WritesLeaveTheCallersBufferAlone) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto& f) {
    f[kData] = 0xEE;  // a (misbehaving) line that changes written data
    set_wkc(f, 1);
    return true;
  });
  Transport t(link, clock);
  const std::array<std::uint8_t, 1> v{0x02};
  EXPECT_EQ(t.fpwr(0x1001, 0x0120, v), 1);
  EXPECT_EQ(v[0], 0x02);
}

}  // namespace
}  // namespace vdrive::master
