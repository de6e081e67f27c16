// TimedLink: turnaround from a frame's arrival to its reply, through a loopback pair.
#include "vdrive/telemetry/timed_link.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "vdrive/link/loopback_link.hpp"

namespace vdrive::telemetry {
namespace {

TEST(TimedLink, MeasuresFrameInToReplyOut) {
  VirtualClock clock(1000);
  auto [master, slave] = link::make_loopback_pair();
  TurnaroundStats stats;
  TimedLink timed(*slave, clock, stats);
  std::vector<std::uint8_t> frame(60, 0);
  frame[12] = 0x88;
  frame[13] = 0xA4;
  std::vector<std::uint8_t> buf(link::kMaxFrame);
  for (const Nanos took : {3000, 1000, 2000}) {
    ASSERT_TRUE(master->send(frame));
    ASSERT_EQ(timed.receive(buf, 0), frame.size());
    clock.advance(took);
    ASSERT_TRUE(timed.send(std::span(buf).first(frame.size())));
  }
  EXPECT_EQ(timed.receive(buf, 0), 0u);
  const TurnaroundPeriod p = stats.take();
  EXPECT_EQ(p.count, 3u);
  EXPECT_EQ(p.last, 2000);
  EXPECT_EQ(p.min, 1000);
  EXPECT_EQ(p.mean, 2000);
  EXPECT_EQ(p.max, 3000);
  EXPECT_EQ(stats.take().count, 0u);  // a new period
  // A send without a frame before it (none today) is not a turnaround.
  ASSERT_TRUE(timed.send(std::span(buf).first(frame.size())));
  EXPECT_EQ(stats.take().count, 0u);
}

}  // namespace
}  // namespace vdrive::telemetry
