// RealtimeWire when the host stalls its one thread: a reply the line owed by the master's
// deadline still counts (the line would have sent it on its own), a reply held past the deadline
// by a wire fault does not. Both ends of the loopback pair move a virtual clock when they wait, as
// a sleeping thread's clock moves; the master's end once sleeps 2 ms too long (the stall).
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/scenario/realtime_wire.hpp"

namespace vdrive::scenario {
namespace {

constexpr Nanos kStall = 2'000'000;
constexpr Nanos kHalfCycle = 500'000;  // the built-in master's wait at a 1 ms cycle

// One end of a loopback pair on a virtual clock: a wait advances the clock by the wait, and by
// kStall more once arm_stall() was called.
class SleepingEnd final : public link::Link {
public:
  SleepingEnd(link::Link& inner, VirtualClock& clock) : inner_(inner), clock_(clock) {}
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    if (const std::size_t n = inner_.receive(buf, 0)) return n;
    if (timeout <= 0) return 0;
    clock_.advance(timeout);
    if (stall_armed_) {
      clock_.advance(kStall);
      stall_armed_ = false;
      ++stalls_;
    }
    return inner_.receive(buf, 0);
  }
  bool send(std::span<const std::uint8_t> frame) override { return inner_.send(frame); }
  int fd() const override { return -1; }

  void arm_stall() { stall_armed_ = true; }
  int stalls() const { return stalls_; }

private:
  link::Link& inner_;
  VirtualClock& clock_;
  bool stall_armed_ = false;
  int stalls_ = 0;
};

class RealtimeWireStall : public ::testing::Test {
protected:
  // Sends one BRD of AL status and waits half a cycle for it, as the runner does each cycle.
  std::size_t exchange() {
    const std::vector<std::uint8_t> frame = test::ethercat_frame(0x07, 0, ecat::reg::kAlStatus, 2);
    EXPECT_TRUE(wire_.send(frame));
    return wire_.receive(reply_, kHalfCycle);
  }
  void delay_replies(Nanos delay) {
    impairment_.set(fault::Direction::to_master, fault::WireSettings{0, 0, 0, 0, delay});
  }

  VirtualClock clock_{1'000'000'000};
  network::Network net_{std::vector<std::string>{"a6b"}, clock_};
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_ =
      link::make_loopback_pair();
  SleepingEnd master_{*ends_.first, clock_};
  SleepingEnd line_{*ends_.second, clock_};
  fault::WireImpairment impairment_{7};
  RealtimeWire wire_{net_, clock_, impairment_, &master_, line_};
  std::array<std::uint8_t, link::kMaxFrame> reply_{};
};

TEST_F(RealtimeWireStall, ReplyHeldInsideTheWaitCountsWhenTheThreadWakesLate) {
  delay_replies(300'000);
  ASSERT_GT(exchange(), 0u);  // no stall: the held reply comes out at 300 us, inside the wait

  master_.arm_stall();  // the thread sleeps through the release and wakes 2 ms late
  const Nanos start = clock_.now();
  EXPECT_GT(exchange(), 0u);
  EXPECT_EQ(master_.stalls(), 1);
  EXPECT_GE(clock_.now() - start, kStall);  // it did come back after the deadline
}

TEST_F(RealtimeWireStall, ReplyHeldPastTheDeadlineStillMissesItsCycle) {
  delay_replies(1'500'000);
  EXPECT_EQ(exchange(), 0u);  // held 1.5 ms against a 0.5 ms wait

  clock_.advance(2'000'000);  // the first reply's time has come: it is delivered, late
  EXPECT_GT(wire_.receive(reply_, 0), 0u);

  master_.arm_stall();  // a stall does not make a late reply count
  EXPECT_EQ(exchange(), 0u);
  EXPECT_EQ(master_.stalls(), 1);
}

}  // namespace
}  // namespace vdrive::scenario
