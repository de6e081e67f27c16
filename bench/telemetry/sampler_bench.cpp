// Cost of the telemetry on the event loop thread (docs/performance.md "Telemetry sampler"):
// Sampler::poll() when no sample is due (paid on every loop iteration, i.e. every frame) and when
// one is (paid once per period: a line of three drives read into the queue). The queue is drained
// outside the timed region, as the publisher thread does.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/telemetry/sampler.hpp"

namespace {

using vdrive::Nanos;

struct Line {
  vdrive::VirtualClock clock{0};
  vdrive::network::Network net{std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock};
  vdrive::runtime::LoopCounters counters;
  vdrive::telemetry::TurnaroundStats turnaround;
};

void BM_PollNothingDue(benchmark::State& state) {
  Line line;
  vdrive::telemetry::Sampler s(line.net, 100.0, {&line.counters, &line.turnaround, nullptr});
  s.poll(0);
  while (s.pop()) {}
  Nanos t = 1;
  for (auto _ : state) {
    s.poll(t);
    t = 1 + (t % 9'000'000);  // always before the next sample at 10 ms
  }
}
BENCHMARK(BM_PollNothingDue);

void BM_PollSampleThreeDrives(benchmark::State& state) {
  Line line;
  vdrive::telemetry::Sampler s(line.net, 1000.0, {&line.counters, &line.turnaround, nullptr});
  Nanos t = 0;
  for (auto _ : state) {
    s.poll(t);  // due every call: 3 axis + 3 bus samples
    t += 1'000'000;
    state.PauseTiming();
    while (s.pop()) {}
    state.ResumeTiming();
  }
}
BENCHMARK(BM_PollSampleThreeDrives);

}  // namespace
