// LoopbackLink: delivery in both directions, EtherType filtering, ring full/empty, and a frame
// exchange between two threads.
#include "vdrive/link/loopback_link.hpp"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <thread>
#include <vector>

namespace vdrive::link {
namespace {

// Broadcast EtherCAT frame carrying `tag` in its first payload byte.
std::vector<std::uint8_t> frame(std::uint8_t tag, std::uint16_t ether_type = kEtherTypeEtherCat, std::size_t len = 60) {
  std::vector<std::uint8_t> f(len, 0);
  for (int i = 0; i < 6; ++i) f[i] = 0xFF;
  f[6] = 0x02;
  f[12] = static_cast<std::uint8_t>(ether_type >> 8);
  f[13] = static_cast<std::uint8_t>(ether_type);
  if (len > 14) f[14] = tag;
  return f;
}

TEST(LoopbackLink, DeliversBothWaysInOrder) {
  auto [a, b] = make_loopback_pair(8);
  ASSERT_TRUE(a->send(frame(1)));
  ASSERT_TRUE(a->send(frame(2)));
  ASSERT_TRUE(b->send(frame(9)));
  std::array<std::uint8_t, kMaxFrame> buf{};
  EXPECT_EQ(b->receive(buf, 0), 60u);
  EXPECT_EQ(buf[14], 1);
  EXPECT_EQ(b->receive(buf, 0), 60u);
  EXPECT_EQ(buf[14], 2);
  EXPECT_EQ(b->receive(buf, 0), 0u);
  EXPECT_EQ(a->receive(buf, 0), 60u);
  EXPECT_EQ(buf[14], 9);
  EXPECT_EQ(a->fd(), -1);
}

TEST(LoopbackLink, KeepsShortFramesAtTheirLength) {
  auto [a, b] = make_loopback_pair();
  ASSERT_TRUE(a->send(frame(3, kEtherTypeEtherCat, 30)));
  std::array<std::uint8_t, kMaxFrame> buf{};
  EXPECT_EQ(b->receive(buf, 0), 30u);
}

TEST(LoopbackLink, DiscardsNonEtherCatFrames) {
  auto [a, b] = make_loopback_pair();
  ASSERT_TRUE(a->send(frame(1, 0x0800)));  // IPv4
  ASSERT_TRUE(a->send(frame(2, 0x88A4, 10)));  // shorter than an Ethernet header
  auto tagged = frame(3, 0x8100, 64);
  tagged[16] = 0x88;
  tagged[17] = 0xA4;
  ASSERT_TRUE(a->send(tagged));
  ASSERT_TRUE(a->send(frame(4)));
  std::array<std::uint8_t, kMaxFrame> buf{};
  EXPECT_EQ(b->receive(buf, 0), 64u);  // VLAN-tagged EtherCAT passes
  EXPECT_EQ(buf[12], 0x81);
  EXPECT_EQ(b->receive(buf, 0), 60u);
  EXPECT_EQ(buf[14], 4);
  EXPECT_EQ(b->receive(buf, 0), 0u);
  EXPECT_EQ(b->discarded(), 2u);
}

TEST(LoopbackLink, FrameWaitingIsAFreeLookThatTakesNothing) {
  auto [a, b] = make_loopback_pair();
  EXPECT_EQ(b->peek_cost(), PeekCost::Free);
  EXPECT_FALSE(b->frame_waiting());
  ASSERT_TRUE(a->send(frame(5)));
  EXPECT_TRUE(b->frame_waiting());
  EXPECT_TRUE(b->frame_waiting());
  EXPECT_FALSE(a->frame_waiting()) << "a frame waits only at the end it was sent to";
  std::array<std::uint8_t, kMaxFrame> buf{};
  EXPECT_EQ(b->receive(buf, 0), 60u);
  EXPECT_EQ(buf[14], 5);
  EXPECT_FALSE(b->frame_waiting());
}

TEST(LoopbackLink, RingFullRefusesAndEmptyReturnsZero) {
  auto [a, b] = make_loopback_pair(4);
  std::array<std::uint8_t, kMaxFrame> buf{};
  EXPECT_EQ(b->receive(buf, 0), 0u);  // empty
  for (std::uint8_t i = 0; i < 4; ++i) EXPECT_TRUE(a->send(frame(i)));
  EXPECT_FALSE(a->send(frame(99)));  // full
  EXPECT_EQ(b->receive(buf, 0), 60u);
  EXPECT_EQ(buf[14], 0);
  EXPECT_TRUE(a->send(frame(4)));  // one slot free again
  for (std::uint8_t i = 1; i <= 4; ++i) {
    ASSERT_EQ(b->receive(buf, 0), 60u);
    EXPECT_EQ(buf[14], i);
  }
  EXPECT_EQ(b->receive(buf, 0), 0u);
}

TEST(LoopbackLink, RefusesOversizedAndDropsTooLongForBuffer) {
  auto [a, b] = make_loopback_pair();
  EXPECT_FALSE(a->send(frame(1, kEtherTypeEtherCat, kMaxFrame + 1)));
  EXPECT_TRUE(a->send(frame(2, kEtherTypeEtherCat, kMaxFrame)));
  EXPECT_TRUE(a->send(frame(3)));
  std::array<std::uint8_t, 100> small{};
  EXPECT_EQ(b->receive(small, 0), 60u);  // the 1518-byte frame did not fit and was dropped
  EXPECT_EQ(small[14], 3);
  EXPECT_EQ(b->discarded(), 1u);
}

TEST(LoopbackLink, TimeoutExpiresWhenNothingArrives) {
  auto [a, b] = make_loopback_pair();
  MonotonicClock clock;
  std::array<std::uint8_t, kMaxFrame> buf{};
  const Nanos start = clock.now();
  EXPECT_EQ(b->receive(buf, 2'000'000), 0u);
  const Nanos waited = clock.now() - start;
  EXPECT_GE(waited, 2'000'000);
  EXPECT_LT(waited, 200'000'000);
}

TEST(LoopbackLink, EchoBetweenThreads) {
  auto [master, network] = make_loopback_pair(16);
  constexpr int kFrames = 2000;
  std::atomic<bool> stop{false};
  std::thread echo([&, net = network.get()] {
    std::array<std::uint8_t, kMaxFrame> buf{};
    while (!stop.load()) {
      const std::size_t n = net->receive(buf, 1'000'000);
      if (n == 0) continue;
      buf[15] = static_cast<std::uint8_t>(buf[14] + 1);  // "processed"
      while (!net->send(std::span(buf).first(n))) std::this_thread::yield();
    }
  });
  std::array<std::uint8_t, kMaxFrame> buf{};
  int ok = 0;
  for (int i = 0; i < kFrames; ++i) {
    const auto f = frame(static_cast<std::uint8_t>(i));
    ASSERT_TRUE(master->send(f));
    const std::size_t n = master->receive(buf, 1'000'000'000);
    ASSERT_EQ(n, 60u);
    if (buf[14] == static_cast<std::uint8_t>(i) && buf[15] == static_cast<std::uint8_t>(i + 1)) ++ok;
  }
  stop = true;
  echo.join();
  EXPECT_EQ(ok, kFrames);
}

}  // namespace
}  // namespace vdrive::link
