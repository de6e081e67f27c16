// Cost of a frame's path through the cabled slaves (Segment::process): N bare ESCs (no firmware)
// cabled as the line, as a chain through ports 3 and 2 (the line's shape, but the tree's walk)
// and as a tree (a four-port junction with a chain on each of ports 3, 1 and 2). One iteration =
// one cyclic-like frame (LRW 32 bytes, BRD of AL status, ARMW of the DC system time) through all
// N. Results and method: docs/performance.md ("Tree topologies").
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/network/segment.hpp"
#include "vdrive/network/topology.hpp"

namespace {

using vdrive::Nanos;
using vdrive::network::Segment;
using vdrive::network::Topology;
using vdrive::network::Uplink;

enum class Shape { line, chain, tree };

// Ethernet header, EtherCAT header, then the datagrams, laid out by hand (ETG.1000.4).
std::vector<std::uint8_t> cyclic_frame() {
  std::vector<std::uint8_t> f = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x11, 0x22, 0x33, 0x44, 0x55, 0x88, 0xA4, 0, 0};
  const auto add = [&](std::uint8_t cmd, std::uint32_t address, std::size_t len, bool more) {
    f.insert(f.end(), {cmd, 0, static_cast<std::uint8_t>(address), static_cast<std::uint8_t>(address >> 8),
                       static_cast<std::uint8_t>(address >> 16), static_cast<std::uint8_t>(address >> 24),
                       static_cast<std::uint8_t>(len), static_cast<std::uint8_t>((len >> 8) | (more ? 0x80 : 0)), 0, 0});
    f.insert(f.end(), len + 2, 0);
  };
  add(0x0C, 0x00010000, 32, true);            // LRW
  add(0x07, 0x01300000, 2, true);             // BRD AL status
  add(0x0D, 0x09100000, 8, false);            // ARMW system time at position 0
  const std::size_t len = f.size() - 16;
  f[14] = static_cast<std::uint8_t>(len);
  f[15] = static_cast<std::uint8_t>(0x10 | (len >> 8));
  return f;
}

void BM_SegmentPath(benchmark::State& state, Shape shape) {
  const auto n = static_cast<std::size_t>(state.range(0));
  vdrive::VirtualClock clock{1'000'000};
  std::vector<std::unique_ptr<vdrive::esc::Esc>> escs;
  Segment segment{500};
  Topology topology;
  for (std::size_t i = 0; i < n; ++i) {
    vdrive::esc::EscConfig config;
    if (shape == Shape::chain || (shape == Shape::tree && i == 0)) config.port_descriptor = 0xFF;
    escs.push_back(std::make_unique<vdrive::esc::Esc>(config, clock));
    segment.append(*escs.back());
    if (i == 0) topology.uplinks.push_back(Uplink{Uplink::kMaster, 0});
    else if (shape == Shape::chain) topology.uplinks.push_back(Uplink{static_cast<int>(i) - 1, i % 2 == 1 ? 3 : 2});
    else if (shape == Shape::tree) {
      // Slaves 1, 2, 3 on the junction's ports 3, 1, 2; then each hangs on port 1 of the one
      // three before it, so the three chains grow evenly.
      const int junction_port[3] = {3, 1, 2};
      topology.uplinks.push_back(i <= 3 ? Uplink{0, junction_port[i - 1]} : Uplink{static_cast<int>(i) - 3, 1});
    }
  }
  if (shape != Shape::line) segment.set_topology(topology);
  std::vector<std::uint8_t> frame = cyclic_frame();
  for (auto _ : state) {
    clock.advance(1'000'000);
    benchmark::DoNotOptimize(segment.process(frame, clock.now()));
  }
  state.counters["per_slave_ns"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK_CAPTURE(BM_SegmentPath, line, Shape::line)->Arg(1)->Arg(8)->Arg(64);
BENCHMARK_CAPTURE(BM_SegmentPath, chain, Shape::chain)->Arg(8)->Arg(64);
BENCHMARK_CAPTURE(BM_SegmentPath, tree, Shape::tree)->Arg(8)->Arg(64);
