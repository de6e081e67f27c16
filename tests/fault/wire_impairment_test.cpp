// fault::WireImpairment: drop, corrupt, duplicate, reorder and delay per direction, determinism by
// seed, bounded storage without allocation; a corrupted frame passed on to the line is counted by
// the ESCs and never reaches the master.
#include "vdrive/fault/wire_impairment.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/network/network.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::fault {
namespace {

constexpr auto kToSlaves = Direction::to_slaves;
constexpr auto kToMaster = Direction::to_master;
constexpr Nanos kNever = std::numeric_limits<Nanos>::max();

std::vector<std::uint8_t> frame(std::uint8_t tag, std::size_t size = 60) {
  std::vector<std::uint8_t> f(size, 0);
  f[0] = tag;
  return f;
}

// Pops everything due at `now`; returns the tags (first byte) in order.
std::vector<int> drain(WireImpairment& w, Direction d, Nanos now) {
  std::array<std::uint8_t, link::kMaxFrame> out{};
  std::vector<int> tags;
  while (const std::size_t n = w.pop(d, out, now)) {
    EXPECT_EQ(n, 60u);
    tags.push_back(out[0]);
  }
  return tags;
}

TEST(WireImpairment, CleanWirePassesEveryFrameAtOnceInOrder) {
  WireImpairment w(1);
  for (std::uint8_t i = 1; i <= 3; ++i) w.push(kToSlaves, frame(i), 100);
  EXPECT_EQ(w.next_release(kToSlaves), 100);
  EXPECT_EQ(w.next_release(kToMaster), kNever);
  EXPECT_EQ(drain(w, kToSlaves, 100), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(w.counters(kToSlaves).passed, 3u);
  EXPECT_EQ(w.counters(kToMaster).passed, 0u);
  EXPECT_EQ(w.next_release(kToSlaves), kNever);
}

TEST(WireImpairment, DelayHoldsEveryFrameAndNeverLetsOneOvertake) {
  WireImpairment w(1);
  w.set(kToMaster, {.delay = 1'000'000});
  w.push(kToMaster, frame(1), 0);
  EXPECT_EQ(w.next_release(kToMaster), 1'000'000);
  EXPECT_TRUE(drain(w, kToMaster, 999'999).empty());
  EXPECT_EQ(drain(w, kToMaster, 1'000'000), (std::vector<int>{1}));

  w.push(kToMaster, frame(2), 2'000'000);   // due at 3 ms
  w.set(kToMaster, {.delay = 100'000});
  w.push(kToMaster, frame(3), 2'100'000);   // would be due at 2.2 ms: waits behind frame 2
  EXPECT_TRUE(drain(w, kToMaster, 2'900'000).empty());
  EXPECT_EQ(drain(w, kToMaster, 3'000'000), (std::vector<int>{2, 3}));
  EXPECT_TRUE(drain(w, kToSlaves, 3'000'000).empty()) << "directions are independent";
}

TEST(WireImpairment, DropLosesFramesAtTheSetRate) {
  WireImpairment w(42);
  w.set(kToSlaves, {.drop = 1.0});
  w.push(kToSlaves, frame(1), 0);
  EXPECT_TRUE(drain(w, kToSlaves, 0).empty());
  EXPECT_EQ(w.counters(kToSlaves).dropped, 1u);

  w.set(kToSlaves, {.drop = 0.3});
  int passed = 0;
  for (int i = 0; i < 10000; ++i) {
    w.push(kToSlaves, frame(7), i);
    passed += static_cast<int>(drain(w, kToSlaves, i).size());
  }
  EXPECT_NEAR(passed, 7000, 200);
  EXPECT_EQ(w.counters(kToSlaves).dropped + w.counters(kToSlaves).passed, 10001u);
}

TEST(WireImpairment, CorruptedFramesComeOutFlaggedAndAReceiverDiscardsThem) {
  WireImpairment w(3);
  w.set(kToMaster, {.corrupt = 1.0});
  w.push(kToMaster, frame(1), 0);
  w.push(kToMaster, frame(2), 0);
  std::array<std::uint8_t, link::kMaxFrame> out{};
  bool fcs_error = false;
  ASSERT_EQ(w.pop(kToMaster, out, 0, fcs_error), 60u);
  EXPECT_TRUE(fcs_error);
  EXPECT_EQ(out[0], 1) << "bytes as sent; the FCS is what is wrong";
  EXPECT_EQ(w.pop(kToMaster, out, 0), 0u) << "the NIC discards frame 2";
  EXPECT_EQ(w.next_release(kToMaster), kNever);
  EXPECT_EQ(w.counters(kToMaster).corrupted, 2u);
  EXPECT_EQ(w.counters(kToMaster).passed, 0u);
}

TEST(WireImpairment, DuplicateComesOutTwiceBackToBack) {
  WireImpairment w(5);
  w.set(kToSlaves, {.duplicate = 1.0});
  w.push(kToSlaves, frame(1), 0);
  w.set(kToSlaves, {});
  w.push(kToSlaves, frame(2), 0);
  EXPECT_EQ(drain(w, kToSlaves, 0), (std::vector<int>{1, 1, 2}));
  EXPECT_EQ(w.counters(kToSlaves).duplicated, 1u);
  EXPECT_EQ(w.counters(kToSlaves).passed, 3u);
}

TEST(WireImpairment, ReorderedFrameComesOutRightAfterTheNextOne) {
  WireImpairment w(9);
  w.set(kToSlaves, {.reorder = 1.0});
  w.push(kToSlaves, frame(1), 0);          // held back
  EXPECT_EQ(w.next_release(kToSlaves), kNever) << "waits for its successor";
  EXPECT_TRUE(drain(w, kToSlaves, 1'000).empty());
  w.push(kToSlaves, frame(2), 2'000);      // not held: one is held already
  EXPECT_EQ(drain(w, kToSlaves, 2'000), (std::vector<int>{2, 1}));
  w.push(kToSlaves, frame(3), 3'000);      // held again
  w.set(kToSlaves, {.drop = 1.0, .reorder = 1.0});
  w.push(kToSlaves, frame(4), 4'000);      // lost: frame 3 comes out in its place
  EXPECT_EQ(drain(w, kToSlaves, 4'000), (std::vector<int>{3}));
  w.set(kToSlaves, {.reorder = 1.0});
  w.push(kToSlaves, frame(5), 5'000);
  w.clear();                               // a clean wire lets the held frame go
  EXPECT_EQ(drain(w, kToSlaves, 5'000), (std::vector<int>{5}));
  const auto& c = w.counters(kToSlaves);
  EXPECT_EQ(c.reordered, 3u);
  EXPECT_EQ(c.dropped, 1u);
  EXPECT_EQ(c.passed, 4u);
}

TEST(WireImpairment, FullQueueAndOversizedFramesAreDropped) {
  WireImpairment w(1, 2);
  w.set(kToSlaves, {.delay = 10});
  for (std::uint8_t i = 1; i <= 3; ++i) w.push(kToSlaves, frame(i), 0);
  w.push(kToSlaves, std::vector<std::uint8_t>(link::kMaxFrame + 1, 0), 0);
  EXPECT_EQ(w.counters(kToSlaves).dropped, 2u);
  EXPECT_EQ(drain(w, kToSlaves, 10), (std::vector<int>{1, 2}));
}

TEST(WireImpairment, SameSeedAndCallsGiveTheSameFramesAndDifferentSeedsDiffer) {
  auto run = [](std::uint64_t seed) {
    WireImpairment w(seed, 16);
    const WireSettings s{.drop = 0.2, .corrupt = 0.2, .duplicate = 0.2, .reorder = 0.2, .delay = 500};
    w.set(kToSlaves, s);
    w.set(kToMaster, s);
    std::vector<int> seen;
    std::array<std::uint8_t, link::kMaxFrame> out{};
    for (int i = 0; i < 500; ++i) {
      const Direction d = (i % 3 == 0) ? kToMaster : kToSlaves;
      w.push(d, frame(static_cast<std::uint8_t>(i)), i * 100);
      for (const Direction e : {kToSlaves, kToMaster}) {
        bool bad = false;
        while (const std::size_t n = w.pop(e, out, i * 100, bad)) {
          seen.push_back(out[0] * 4 + (bad ? 2 : 0) + static_cast<int>(e));
          EXPECT_EQ(n, 60u);
        }
      }
    }
    return seen;
  };
  EXPECT_EQ(run(1234), run(1234));
  EXPECT_NE(run(1234), run(1235));
}

TEST(WireImpairment, PushAndPopAllocateNothing) {
  WireImpairment w(77, 8);
  w.set(kToSlaves, {.drop = 0.1, .corrupt = 0.1, .duplicate = 0.3, .reorder = 0.3, .delay = 50});
  const auto f = frame(1);
  std::array<std::uint8_t, link::kMaxFrame> out{};
  const long before = vdrive::test::allocation_count();
  for (int i = 0; i < 1000; ++i) {
    w.push(kToSlaves, f, i * 10);
    bool bad = false;
    while (w.pop(kToSlaves, out, i * 10, bad) != 0) {
    }
  }
  w.clear();
  EXPECT_EQ(vdrive::test::allocation_count(), before);
}

// The caller's part for corrupt: a flagged frame to the slaves goes to
// Segment::process_corrupted(), which the ESCs count; the master gets no reply.
TEST(WireImpairment, CorruptedFrameToTheSlavesIsCountedByTheEscsAndNeverAnswered) {
  VirtualClock clock(1'000'000);
  network::Network net(std::vector<std::string>{"a6b", "ds5c1"}, clock);
  WireImpairment w(11);
  w.set(kToSlaves, {.corrupt = 1.0});
  auto write = test::ethercat_frame(0x08, 0, ecat::reg::kUserRam, std::vector<std::uint8_t>{0xAB});  // BWR 0x0F80
  w.push(kToSlaves, write, clock.now());
  std::array<std::uint8_t, link::kMaxFrame> buf{};
  bool fcs_error = false;
  const std::size_t n = w.pop(kToSlaves, buf, clock.now(), fcs_error);
  ASSERT_EQ(n, write.size());
  ASSERT_TRUE(fcs_error);
  net.segment().process_corrupted(std::span<const std::uint8_t>(buf.data(), n), clock.now());
  EXPECT_EQ(net.esc(0).peek(ecat::reg::kUserRam), 0) << "not executed";
  EXPECT_EQ(net.esc(0).peek(ecat::reg::kRxErrorCounter), 1) << "slave 1: invalid frame, port 0";
  EXPECT_EQ(net.esc(1).peek(ecat::reg::kRxErrorCounter), 0);
  EXPECT_EQ(net.esc(1).peek(ecat::reg::kForwardedRxErrorCounter), 1) << "slave 2: forwarded error";

  w.clear();  // healed: the same write goes through
  w.push(kToSlaves, write, clock.now());
  const std::size_t m = w.pop(kToSlaves, buf, clock.now(), fcs_error);
  ASSERT_FALSE(fcs_error);
  EXPECT_TRUE(net.process_frame(std::span<std::uint8_t>(buf.data(), m), clock.now()));
  EXPECT_EQ(net.esc(0).peek(ecat::reg::kUserRam), 0xAB);
}

}  // namespace
}  // namespace vdrive::fault
