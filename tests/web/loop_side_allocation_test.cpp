// What the web server puts on the loop thread allocates nothing while no request is pending: the
// Sampler at the page's rate and LoopCalls with an empty queue, polled together as WebServer
// polls them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/support/allocation_counter.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/telemetry/loop_services.hpp"
#include "vdrive/telemetry/sampler.hpp"
#include "vdrive/web/loop_calls.hpp"

namespace vdrive::web {
namespace {

TEST(WebLoopSide, PollingWithNothingPendingAllocatesNothing) {
  VirtualClock clock(0);
  network::Network net(std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock);
  runtime::LoopCounters counters;
  telemetry::Sampler sampler(net, 50.0, telemetry::SamplerSources{&counters, nullptr, nullptr});
  LoopCalls calls;
  telemetry::LoopServices services(&sampler, &calls);
  services.poll(0);
  const long before = vdrive::test::allocation_count();
  for (Nanos t = 250'000; t < 2'000'000'000; t += 250'000) services.poll(t);  // 100 samples, 8000 polls
  EXPECT_EQ(vdrive::test::allocation_count() - before, 0);
  int samples = 0;
  while (sampler.pop()) ++samples;
  EXPECT_GE(samples, 100);  // it did sample all along
}

}  // namespace
}  // namespace vdrive::web
