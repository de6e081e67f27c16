// ImpairedLink on the serving path allocates nothing: with a clean wire (the inner link after
// one branch) and with every impairment engaged (drop, corrupt into process_corrupted,
// duplicate, reorder, delay). Counts with tests/support/allocation_counter.hpp.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/fault/impaired_link.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::fault {
namespace {

class ImpairedLinkNoAllocation : public ::testing::Test {
protected:
  // Sends 20 rounds of frames through the loop behind the impaired link; returns allocations.
  long serve_rounds() {
    const std::vector<std::uint8_t> frame = test::ethercat_frame(0x07, 0, ecat::reg::kAlStatus, 2);
    std::array<std::uint8_t, link::kMaxFrame> reply{};
    const long before = vdrive::test::allocation_count();
    for (int round = 0; round < 20; ++round) {
      for (int i = 0; i < 4; ++i) EXPECT_TRUE(ends_.first->send(frame));
      runtime::run_until(net_, impaired_, clock_, clock_.now() + 1'000'000, counters_);
      clock_.advance(2'000'000);  // past every delay
      runtime::run_pending(net_, impaired_, clock_, counters_);
      while (ends_.first->receive(reply, 0) != 0) {
      }
    }
    return vdrive::test::allocation_count() - before;
  }

  VirtualClock clock_{1'000'000};
  network::Network net_{std::vector<std::string>{"a6b", "ds5c1"}, clock_};
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_ = link::make_loopback_pair();
  WireImpairment wire_{3};
  ImpairedLink impaired_{*ends_.second, wire_, net_, clock_};
  runtime::LoopCounters counters_;
};

TEST_F(ImpairedLinkNoAllocation, CleanWire) {
  serve_rounds();  // warm-up
  EXPECT_FALSE(impaired_.engaged());
  EXPECT_EQ(serve_rounds(), 0);
  EXPECT_EQ(counters_.frames_out.load(), 160u);  // every frame answered
}

TEST_F(ImpairedLinkNoAllocation, EveryImpairmentEngaged) {
  wire_.set(Direction::to_slaves, WireSettings{0.2, 0.2, 0.2, 0.2, 300'000});
  wire_.set(Direction::to_master, WireSettings{0.1, 0.1, 0.2, 0.2, 500'000});
  impaired_.refresh();
  ASSERT_TRUE(impaired_.engaged());
  serve_rounds();  // warm-up
  EXPECT_EQ(serve_rounds(), 0);
  const WireImpairment::Counters& c = wire_.counters(Direction::to_slaves);
  EXPECT_GT(c.dropped, 0u);
  EXPECT_GT(c.corrupted, 0u);
  EXPECT_GT(c.duplicated, 0u);
  EXPECT_GT(c.reordered, 0u);
}

}  // namespace
}  // namespace vdrive::fault
