// RawSocketLink with busy polling (Options::busy_poll) on a veth pair the test creates: frames are
// received during and after the spin window, the spin never outlasts the caller's timeout, and a
// poll (timeout 0) does not spin. Needs root; skipped otherwise. How much the spin saves is measured
// by bench/turnaround/run.sh, not here.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "tests/support/runtime_test_support.hpp"
#include "vdrive/link/raw_socket_link.hpp"

namespace vdrive::link {
namespace {

using test::ethercat_frame;
using std::chrono::milliseconds;
using std::chrono::steady_clock;

constexpr Nanos kMs = 1'000'000;

class BusyPollTest : public ::testing::Test {
protected:
  void open(Nanos busy_poll) {
    if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
    veth_ = std::make_unique<test::VethPair>();
    ASSERT_TRUE(veth_->ok()) << "could not create a veth pair";
    a_ = std::make_unique<RawSocketLink>(veth_->a());
    RawSocketLink::Options options;
    options.busy_poll = busy_poll;
    b_ = std::make_unique<RawSocketLink>(veth_->b(), options);
  }
  std::unique_ptr<test::VethPair> veth_;
  std::unique_ptr<RawSocketLink> a_, b_;
  std::array<std::uint8_t, kMaxFrame> buf_{};
};

TEST_F(BusyPollTest, FrameArrivingDuringTheSpinIsReceived) {
  open(2000 * kMs);
  if (IsSkipped()) return;
  const auto frame = ethercat_frame(0x07, 0, 0x0130, 2);
  std::thread sender([&] {
    std::this_thread::sleep_for(milliseconds(20));
    a_->send(frame);
  });
  const std::size_t n = b_->receive(buf_, 1000 * kMs);
  sender.join();
  ASSERT_EQ(n, frame.size());
  EXPECT_TRUE(std::equal(frame.begin(), frame.end(), buf_.begin()));
}

TEST_F(BusyPollTest, FrameArrivingAfterTheSpinIsStillReceived) {
  open(5 * kMs);  // spins 5 ms, then sleeps in ppoll for the rest of the timeout
  if (IsSkipped()) return;
  const auto frame = ethercat_frame(0x01, 0, 0x0010, 2);
  std::thread sender([&] {
    std::this_thread::sleep_for(milliseconds(100));
    a_->send(frame);
  });
  const std::size_t n = b_->receive(buf_, 2000 * kMs);
  sender.join();
  ASSERT_EQ(n, frame.size());
  EXPECT_TRUE(std::equal(frame.begin(), frame.end(), buf_.begin()));
}

TEST_F(BusyPollTest, SpinNeverOutlastsTheTimeout) {
  open(5000 * kMs);
  if (IsSkipped()) return;
  const auto start = steady_clock::now();
  EXPECT_EQ(b_->receive(buf_, 50 * kMs), 0u);
  const auto waited = steady_clock::now() - start;
  EXPECT_GE(waited, milliseconds(45));
  EXPECT_LT(waited, milliseconds(2500));  // far below the 5 s window: the timeout ended the spin
}

TEST_F(BusyPollTest, PollDoesNotSpin) {
  open(5000 * kMs);
  if (IsSkipped()) return;
  const auto start = steady_clock::now();
  EXPECT_EQ(b_->receive(buf_, 0), 0u);
  EXPECT_LT(steady_clock::now() - start, milliseconds(2500));
  // A frame already waiting is returned by a poll as before.
  const auto frame = ethercat_frame(0x07, 0, 0, 2);
  ASSERT_TRUE(a_->send(frame));
  std::size_t n = 0;
  for (int i = 0; i < 200 && n == 0; ++i) {
    n = b_->receive(buf_, 0);
    if (n == 0) std::this_thread::sleep_for(milliseconds(5));
  }
  EXPECT_EQ(n, frame.size());
}

TEST_F(BusyPollTest, OwnSendsAndOtherTrafficAreStillFilteredWhileSpinning) {
  open(200 * kMs);
  if (IsSkipped()) return;
  ASSERT_TRUE(b_->send(ethercat_frame(0x07, 0, 0, 2)));  // our own: never returned
  ASSERT_TRUE(a_->send(test::ethernet_frame(0x0800, std::vector<std::uint8_t>(46, 0x45))));  // not EtherCAT
  EXPECT_EQ(b_->receive(buf_, 100 * kMs), 0u);
}

}  // namespace
}  // namespace vdrive::link
