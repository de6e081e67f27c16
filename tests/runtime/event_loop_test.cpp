// The event loop between a LoopbackLink (the master's end in the test) and a Network of real
// product slaves: in virtual time (run_until/run_pending) and in real time on a thread (serve).
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/runtime/loopback_line_test.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/link/link_error.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::runtime {
namespace {

using test::ethercat_frame;
using test::first_wkc;

constexpr std::uint8_t kBrd = 0x07;
constexpr Nanos kMs = 1'000'000;

std::vector<std::uint8_t> take(link::Link& master, Nanos timeout = 0) {
  std::array<std::uint8_t, link::kMaxFrame> buf{};
  const std::size_t n = master.receive(buf, timeout);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
}

class VirtualLoopTest : public test::LoopbackLineTest {
protected:
  VirtualLoopTest() : LoopbackLineTest({"a6b", "ds5c1"}, 5 * kMs) {}
};

TEST_F(VirtualLoopTest, PendingFrameIsAnsweredWithoutTimeMoving) {
  ASSERT_TRUE(master_.send(ethercat_frame(kBrd, 0, ecat::reg::kType, 1)));
  run_pending(net_, line_, clock_, counters_);
  EXPECT_EQ(clock_.now(), 5 * kMs);
  const auto reply = take(master_);
  ASSERT_FALSE(reply.empty());
  EXPECT_EQ(first_wkc(reply), 2);
  EXPECT_EQ(counters_.frames_in.load(), 1u);
  EXPECT_EQ(counters_.frames_out.load(), 1u);
  EXPECT_EQ(counters_.dropped.load(), 0u);
}

TEST_F(VirtualLoopTest, EveryQueuedFrameIsAnsweredInOrder) {
  for (std::uint16_t ado : {ecat::reg::kType, ecat::reg::kRevision, ecat::reg::kBuild}) {
    ASSERT_TRUE(master_.send(ethercat_frame(kBrd, 0, ado, 1)));
  }
  run_pending(net_, line_, clock_, counters_);
  for (std::uint16_t ado : {ecat::reg::kType, ecat::reg::kRevision, ecat::reg::kBuild}) {
    const auto reply = take(master_);
    ASSERT_FALSE(reply.empty());
    EXPECT_EQ(reply[14 + 2 + 4] | (reply[14 + 2 + 5] << 8), ado);  // datagram address offset
  }
  EXPECT_TRUE(take(master_).empty());
  EXPECT_EQ(counters_.frames_out.load(), 3u);
}

TEST_F(VirtualLoopTest, DestroyedFrameIsCountedAndGetsNoReply) {
  auto frame = ethercat_frame(kBrd, 0, ecat::reg::kType, 8);
  frame.resize(frame.size() - 6);  // the datagram runs past the end of the frame
  ASSERT_TRUE(master_.send(frame));
  run_pending(net_, line_, clock_, counters_);
  EXPECT_TRUE(take(master_).empty());
  EXPECT_EQ(counters_.frames_in.load(), 1u);
  EXPECT_EQ(counters_.dropped.load(), 1u);
  EXPECT_EQ(counters_.frames_out.load(), 0u);
}

TEST_F(VirtualLoopTest, RunUntilLeavesTheClockAtTheTargetAndNeverGoesBack) {
  run_until(net_, line_, clock_, 50 * kMs, counters_);
  EXPECT_EQ(clock_.now(), 50 * kMs);
  EXPECT_GT(net_.next_deadline(), 50 * kMs) << "every timer due by then has run";
  run_until(net_, line_, clock_, 20 * kMs, counters_);
  EXPECT_EQ(clock_.now(), 50 * kMs);
}

TEST_F(VirtualLoopTest, FramesSentLaterAreAnsweredAtTheirTime) {
  run_until(net_, line_, clock_, 10 * kMs, counters_);
  ASSERT_TRUE(master_.send(ethercat_frame(kBrd, 0, ecat::reg::kType, 1)));
  run_until(net_, line_, clock_, 11 * kMs, counters_);
  EXPECT_EQ(first_wkc(take(master_)), 2);
  EXPECT_EQ(clock_.now(), 11 * kMs);
}

TEST(RealTimeLoop, ServesOnAThreadAndStopsWhenAsked) {
  MonotonicClock clock;
  network::Network net(std::vector<std::string>{"ds1000a"}, clock);
  auto ends = link::make_loopback_pair();  // no structured binding: clang 14 cannot capture one
  link::Link* master = ends.first.get();
  link::Link* line = ends.second.get();
  std::atomic<bool> stop{false};
  LoopCounters counters;
  std::thread loop([&] { serve(net, *line, clock, stop, counters); });

  ASSERT_TRUE(master->send(ethercat_frame(kBrd, 0, ecat::reg::kType, 1)));
  const auto reply = take(*master, 1000 * kMs);
  EXPECT_EQ(reply.empty() ? -1 : first_wkc(reply), 1);

  const auto asked = std::chrono::steady_clock::now();
  stop = true;
  loop.join();
  // kMaxWait bounds the wait; allow generous slack for a loaded machine.
  EXPECT_LT(std::chrono::steady_clock::now() - asked, std::chrono::milliseconds(500));
  EXPECT_EQ(counters.frames_in.load(), 1u);
  EXPECT_EQ(counters.frames_out.load(), 1u);
}

// A link whose interface has vanished: every receive() throws, as RawSocketLink does then.
class VanishedLink final : public link::Link {
public:
  std::size_t receive(std::span<std::uint8_t>, Nanos) override {
    throw link::LinkError(link::LinkError::Kind::NoInterface, "interface 'x' disappeared");
  }
  bool send(std::span<const std::uint8_t>) override { return false; }
};

TEST(RealTimeLoop, ALinkErrorEndsServing) {
  MonotonicClock clock;
  network::Network net(std::vector<std::string>{"a6b"}, clock);
  VanishedLink gone;
  std::atomic<bool> stop{false};
  LoopCounters counters;
  EXPECT_THROW(serve(net, gone, clock, stop, counters), link::LinkError);
  EXPECT_EQ(counters.frames_in.load(), 0u);
}

}  // namespace
}  // namespace vdrive::runtime
