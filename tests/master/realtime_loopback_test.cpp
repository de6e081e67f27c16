// The master and the event loop on two threads over a LoopbackLink pair, in real time: the way
// `vdrive demo` runs them, minus the veth pair.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "master/master.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::master {
namespace {

TEST(RealTimeLoopback, ScanAndPreOpWithTheEventLoopOnItsOwnThread) {
  const std::vector<std::string> products{"a6b", "ds5c1", "ds1000a"};
  MonotonicClock clock;
  network::Network net(products, clock);
  auto ends = link::make_loopback_pair();
  link::Link& master_end = *ends.first;
  link::Link& line_end = *ends.second;
  std::atomic<bool> stop{false};
  runtime::LoopCounters counters;
  std::thread loop([&] { runtime::serve(net, line_end, clock, stop, counters); });

  bool reached = false;
  std::size_t found = 0;
  {
    Master m(master_end);
    found = m.scan();
    reached = m.request_state(AlState::PreOp);
    for (const Slave& s : m.slaves()) EXPECT_EQ(s.state(), AlState::PreOp) << s.info.name;
  }
  stop.store(true);
  loop.join();

  EXPECT_EQ(found, 3u);
  EXPECT_TRUE(reached);
  EXPECT_EQ(counters.frames_in.load(), counters.frames_out.load()) << "every frame came back";
  EXPECT_EQ(counters.dropped.load(), 0u);
}

}  // namespace
}  // namespace vdrive::master
