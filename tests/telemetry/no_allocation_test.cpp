// The Sampler allocates nothing on the loop thread once constructed: polls with nothing due,
// samples of every slave, a full queue, and events (fault started/ended, a named signal changed,
// as the sampler notices them). Global operator new is replaced for the whole test_telemetry binary by a counting one; it
// only counts, so every other test behaves as before. Control requests are the exception, as with
// the control socket's FaultService: carrying out a fault request allocates.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/telemetry/sampler.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vdrive::telemetry {
namespace {

TEST(SamplerNoAllocation, PollsSamplesDropsAndFaultEventsAllocateNothing) {
  VirtualClock clock(0);
  network::NetworkOptions o;
  o.signals = {{"home", network::SignalPoint{0, network::PlantConnection::home, 0, 0}, ""}};
  network::Network net(std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock, o);
  runtime::LoopCounters counters;
  TurnaroundStats turnaround;
  fault::FaultInjector faults(net, nullptr);
  Sampler s(net, 1000.0, SamplerSources{&counters, &turnaround, &faults});
  s.poll(0);

  fault::FaultSpec spec;
  spec.kind = fault::FaultKind::encoder_error;
  spec.slave = 2;
  const int id = faults.inject(spec, 500'000);  // allocates (the injector's list), before counting

  const long before = g_allocations.load();
  Nanos t = 1'000'000;
  for (; t < 3'000'000'000; t += 250'000) {  // 4 polls per sample; the queue fills and drops
    if (t % 100'000'000 == 0) net.signal(0).write(net.signal(0).read() ^ 1);  // signal events too
    s.poll(t);
  }
  const long during = g_allocations.load() - before;
  EXPECT_EQ(during, 0);
  EXPECT_GT(s.dropped(), 0u);

  faults.clear(id, t);
  const long before_end = g_allocations.load();
  s.poll(t + 1'000'000);  // notices the fault's end: an event into a full queue
  EXPECT_EQ(g_allocations.load() - before_end, 0);
}

}  // namespace
}  // namespace vdrive::telemetry
