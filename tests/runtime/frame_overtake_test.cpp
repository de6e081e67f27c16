// FrameOvertake: in real time a frame that arrives while the line's firmware runs goes back
// between two slaves' firmware calls, its interrupts are serviced after the batch, a system-call
// peek is rationed, a flood cannot starve the firmware, and nothing overtakes where the link
// cannot tell (an impaired wire) or in virtual time.
#include "vdrive/runtime/frame_overtake.hpp"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/runtime/loopback_line_test.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/fault/impaired_link.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::runtime {
namespace {

using test::ethercat_frame;
using test::first_wkc;

constexpr std::uint8_t kBrd = 0x07;
constexpr std::uint8_t kBwr = 0x08;
constexpr Nanos kMs = 1'000'000;

// The line's end of a loopback pair, with every look at it counted. A frame handed to
// arrive_at_peek(k, ...) reaches the link only at its k-th look, i.e. after the k-th firmware
// call of a batch: a frame that lands while the firmware runs. send() notes at which look it went.
class CountingLink final : public link::Link {
public:
  CountingLink(link::Link& line, link::Link& master, link::PeekCost cost) : line_(line), master_(master), cost_(cost) {}

  void arrive_at_peek(int k, std::vector<std::uint8_t> frame) {
    arrive_at_ = k;
    pending_ = std::move(frame);
  }
  link::PeekCost peek_cost() const override { return cost_; }
  bool frame_waiting() override {
    look();
    return line_.frame_waiting();
  }
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    if (cost_ != link::PeekCost::Free) look();  // for such links a receive is the look
    return line_.receive(buf, timeout);
  }
  bool send(std::span<const std::uint8_t> frame) override {
    sent_at_.push_back(looks_);
    return line_.send(frame);
  }

  int looks() const { return looks_; }
  const std::vector<int>& sent_at() const { return sent_at_; }

private:
  void look() {
    ++looks_;
    if (pending_ && looks_ == arrive_at_) {
      ASSERT_TRUE(master_.send(*pending_));
      pending_.reset();
    }
  }
  link::Link& line_;
  link::Link& master_;
  link::PeekCost cost_;
  int looks_ = 0;
  int arrive_at_ = 0;
  std::optional<std::vector<std::uint8_t>> pending_;
  std::vector<int> sent_at_;
};

std::vector<std::uint8_t> take(link::Link& master) {
  std::array<std::uint8_t, link::kMaxFrame> buf{};
  const std::size_t n = master.receive(buf, 0);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
}

class FrameOvertakeTest : public test::LoopbackLineTest {
protected:
  FrameOvertakeTest() : LoopbackLineTest({"a6b", "ds5c1", "ds1000a"}, 0) {}

  // One loop round at `clock_`, with every timer of the three drives due (1 ms after power-on).
  void serve_round(link::Link& link) {
    clock_.set(kMs);
    ASSERT_LE(net_.next_deadline(), clock_.now()) << "the round must start with firmware timers due";
    serve_once(net_, link, clock_, clock_.now(), counters_);
  }
};

TEST_F(FrameOvertakeTest, FrameArrivingWhileFirmwareRunsGoesBackBeforeTheRestOfTheLine) {
  CountingLink link(line_, master_, link::PeekCost::Free);
  link.arrive_at_peek(1, ethercat_frame(kBrd, 0, ecat::reg::kType, 1));
  serve_round(link);

  ASSERT_EQ(link.sent_at().size(), 1u);
  EXPECT_EQ(link.sent_at()[0], 1) << "answered at the first look, right after the first firmware call";
  EXPECT_GE(link.looks(), 3) << "the other slaves' firmware ran after the reply had gone";
  EXPECT_EQ(first_wkc(take(master_)), 3);
  EXPECT_EQ(counters_.frames_in.load(), 1u);
  EXPECT_EQ(counters_.frames_out.load(), 1u);
}

TEST_F(FrameOvertakeTest, WithoutAPeekTheFrameWaitsForTheBatch) {
  CountingLink link(line_, master_, link::PeekCost::Unsupported);
  link.arrive_at_peek(1, ethercat_frame(kBrd, 0, ecat::reg::kType, 1));  // at the round's receive
  serve_round(link);

  EXPECT_EQ(link.looks(), 1) << "asked only by the round's own receive, after the batch";
  ASSERT_EQ(link.sent_at().size(), 1u);
  EXPECT_EQ(first_wkc(take(master_)), 3);
}

TEST_F(FrameOvertakeTest, InterruptsOfAFrameThatOvertookAreServicedAfterTheBatch) {
  CountingLink link(line_, master_, link::PeekCost::Free);
  // Every slave is asked for Pre-Op: an AL control event for each firmware.
  link.arrive_at_peek(1, ethercat_frame(kBwr, 0, ecat::reg::kAlControl, std::vector<std::uint8_t>{0x02, 0x00}));
  serve_round(link);

  ASSERT_EQ(first_wkc(take(master_)), 3);
  for (std::size_t i = 0; i < net_.size(); ++i) {
    EXPECT_EQ(net_.esc(i).pdi_irq(), 0u) << "slave " << i << ": its AL control event is still unserviced";
    std::array<std::uint8_t, 2> status{};
    net_.esc(i).pdi_read(ecat::reg::kAlStatus, status);
    EXPECT_NE(status[0], 0x01) << "slave " << i << ": still plain Init, its firmware never saw the request";
  }
}

TEST_F(FrameOvertakeTest, FramesWaitingBehindAFrameGoBackBeforeTheFirmwareReacts) {
  // A cycle split over three frames: all wait when the round receives the first.
  CountingLink link(line_, master_, link::PeekCost::Free);
  run_until(net_, line_, clock_, kMs, counters_);
  ASSERT_GT(net_.next_deadline(), clock_.now()) << "no firmware timer may run in the round";
  for (std::uint16_t ado : {ecat::reg::kType, ecat::reg::kRevision, ecat::reg::kBuild}) {
    ASSERT_TRUE(master_.send(ethercat_frame(kBrd, 0, ado, 1)));
  }
  serve_once(net_, link, clock_, clock_.now(), counters_);
  EXPECT_EQ(counters_.frames_out.load(), 3u) << "one round answers every frame already waiting";
  for (int i = 0; i < 3; ++i) EXPECT_EQ(first_wkc(take(master_)), 3);
}

TEST_F(FrameOvertakeTest, ASystemCallPeekIsMadeOncePerInterval) {
  CountingLink link(line_, master_, link::PeekCost::SystemCall);
  FrameOvertake overtake(net_, link, clock_, counters_, clock_.now());
  ASSERT_NE(overtake.hook(), nullptr);
  overtake.run();
  clock_.set(kSyscallPeekInterval - 1);
  overtake.run();
  EXPECT_EQ(link.looks(), 0) << "not before the interval has passed since the round began";
  clock_.set(kSyscallPeekInterval);
  overtake.run();
  overtake.run();
  EXPECT_EQ(link.looks(), 1);
  clock_.set(2 * kSyscallPeekInterval);
  overtake.run();
  EXPECT_EQ(link.looks(), 2);
}

TEST_F(FrameOvertakeTest, AFloodIsTakenInBoundedGulps) {
  constexpr int kFlood = 40;
  for (int i = 0; i < kFlood; ++i) ASSERT_TRUE(master_.send(ethercat_frame(kBrd, 0, ecat::reg::kType, 1)));
  FrameOvertake overtake(net_, line_, clock_, counters_, clock_.now());
  overtake.run();
  EXPECT_EQ(counters_.frames_out.load(), static_cast<std::uint64_t>(kMaxFramesInOneGo));
  overtake.service_owed_irqs();
  overtake.run();
  EXPECT_EQ(counters_.frames_out.load(), static_cast<std::uint64_t>(2 * kMaxFramesInOneGo));
}

TEST_F(FrameOvertakeTest, AnImpairedWireLetsNothingOvertake) {
  fault::WireImpairment wire(1);
  fault::ImpairedLink impaired(line_, wire, net_, clock_);
  EXPECT_EQ(impaired.peek_cost(), link::PeekCost::Free) << "a clean wire is the inner link's";
  fault::WireSettings delayed;
  delayed.delay = 100'000;
  wire.set(fault::Direction::to_slaves, delayed);
  impaired.refresh();
  ASSERT_TRUE(master_.send(ethercat_frame(kBrd, 0, ecat::reg::kType, 1)));
  EXPECT_EQ(impaired.peek_cost(), link::PeekCost::Unsupported);
  EXPECT_FALSE(impaired.frame_waiting()) << "when a delayed frame arrives is the wire's to say";
  FrameOvertake overtake(net_, impaired, clock_, counters_, clock_.now());
  EXPECT_EQ(overtake.hook(), nullptr);
}

TEST_F(FrameOvertakeTest, VirtualTimeNeverLooks) {
  CountingLink link(line_, master_, link::PeekCost::Free);
  ASSERT_TRUE(master_.send(ethercat_frame(kBrd, 0, ecat::reg::kType, 1)));
  run_until(net_, link, clock_, 5 * kMs, counters_);
  EXPECT_EQ(link.looks(), 0);
  EXPECT_EQ(first_wkc(take(master_)), 3);
}

}  // namespace
}  // namespace vdrive::runtime
