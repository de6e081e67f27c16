// The serving path allocates nothing once the line is built (architecture rule): frames through
// the LoopbackLink, the Network (segment, ESCs, firmware IRQs) and the event loop, plus timers.
// Counts with tests/support/allocation_counter.hpp.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::runtime {
namespace {

TEST(RuntimeNoAllocation, ServingFramesAndTimersAllocatesNothing) {
  VirtualClock clock(1'000'000);
  network::Network net(std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock);
  auto [master, line] = link::make_loopback_pair();
  LoopCounters counters;

  // Reads, writes (station addresses, AL control requests the firmware answers, a refused one),
  // and a malformed frame: every path a frame can take, built before counting starts.
  std::vector<std::vector<std::uint8_t>> frames = {
      test::ethercat_frame(0x07, 0, ecat::reg::kType, 8),                       // BRD
      test::ethercat_frame(0x02, 0, ecat::reg::kStationAddress, {0x01, 0x10}),  // APWR
      test::ethercat_frame(0x04, 0x1001, ecat::reg::kAlStatus, 6),              // FPRD
      test::ethercat_frame(0x08, 0, ecat::reg::kAlControl, {0x04, 0x00}),       // BWR: Safe-Op, refused
      test::ethercat_frame(0x08, 0, ecat::reg::kAlControl, {0x11, 0x00}),       // BWR: Init + ack
      test::ethercat_frame(0x07, 0, ecat::reg::kAlStatus, 2),
  };
  auto truncated = test::ethercat_frame(0x07, 0, ecat::reg::kType, 8);
  truncated.resize(truncated.size() - 6);
  frames.push_back(truncated);
  std::array<std::uint8_t, link::kMaxFrame> reply{};

  // One warm-up round, so anything lazily sized on first use is not counted.
  for (const auto& f : frames) ASSERT_TRUE(master->send(f));
  run_until(net, *line, clock, clock.now() + 1'000'000, counters);
  while (master->receive(reply, 0) != 0) {
  }

  // The counter works: an explicit call of the global operator new (never elided) counts.
  const long probe = vdrive::test::allocation_count();
  ::operator delete(::operator new(16));
  ASSERT_EQ(vdrive::test::allocation_count() - probe, 1) << "counting operator new not installed";

  const long before = vdrive::test::allocation_count();
  for (int round = 0; round < 20; ++round) {
    for (const auto& f : frames) ASSERT_TRUE(master->send(f));
    run_until(net, *line, clock, clock.now() + 1'000'000, counters);
    while (master->receive(reply, 0) != 0) {
    }
  }
  EXPECT_EQ(vdrive::test::allocation_count() - before, 0);
  EXPECT_EQ(counters.frames_in.load(), 21u * frames.size());
  EXPECT_EQ(counters.dropped.load(), 21u);  // only the truncated frame
}

}  // namespace
}  // namespace vdrive::runtime
