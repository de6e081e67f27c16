#pragma once
// A line of N drives in one process, run by the project master as a PLC would: scan, Pre-Op,
// process data, DC with SYNC0 at the cycle time, Safe-Op, Op, every drive enabled in cyclic
// synchronous position following a sine (master/cia402_program.hpp) with its default plant.
// Virtual time: the master's link runs the event loop (runtime::run_until) for the round trip.
//
// After bring_up(), cycle() is one bus cycle of steady state: the master's frames (LRW of the
// process image, in as many pieces and frames as it needs past ~71 drives; FRMW of the DC
// reference time and BRD of the AL status in the first) through the line, then every
// ESC/firmware/drive/plant timer up to the next cycle. The benchmarks under bench/ time it.
#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/clock.hpp"
#include "master/cia402_program.hpp"
#include "master/cyclic_task.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::bench {

// The products in turn: a6b, ds5c1, ds1000a, a6b, ... (`a6b_only`: the A6B alone, the only one
// of the three that runs a 125 us cycle).
inline std::vector<std::string> product_mix(std::size_t n, bool a6b_only) {
  static const char* const kMix[] = {"a6b", "ds5c1", "ds1000a"};
  std::vector<std::string> ids;
  for (std::size_t i = 0; i < n; ++i) ids.emplace_back(a6b_only ? "a6b" : kMix[i % 3]);
  return ids;
}

class CspLine final : public link::Link {
public:
  static constexpr Nanos kRoundTrip = 20'000;  // wire time of a frame there and back

  explicit CspLine(std::vector<std::string> products)
      : products_(std::move(products)), network_(products_, clock_), ends_(link::make_loopback_pair()) {}

  bool send(std::span<const std::uint8_t> frame) override { return ends_.first->send(frame); }
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    const Nanos start = clock_.now();
    advance_to(start + std::min<Nanos>(kRoundTrip, std::max<Nanos>(timeout, 0)));
    if (const std::size_t n = ends_.first->receive(buf, 0)) return n;
    advance_to(start + std::max<Nanos>(timeout, 0));
    return ends_.first->receive(buf, 0);
  }

  // Scan, Op with DC at `cycle`, drives enabled in csp; `warmup` cycles in Op. Throws
  // std::runtime_error when the line does not get there.
  void bring_up(Nanos cycle, std::uint64_t warmup = 500) {
    master_ = std::make_unique<master::Master>(*this, clock_);
    if (master_->scan() != products_.size()) throw std::runtime_error("scan: wrong slave count");
    master::SineProgramOptions sine;
    sine.cycle = cycle;
    sine.frequency_hz = 1.0;
    sine.settle = 100'000'000;
    sine.motion = Nanos{1} << 60;  // never done: the drives move for as long as the benchmark runs
    program_ = std::make_unique<master::SineProgram>(sine);
    master::OpRunOptions op;
    op.cycle = cycle;
    op.dc = true;
    op.drift_frames = 200;
    op.mailbox_timeout = 20'000'000;
    op.cycles = warmup;
    op.back_to_init = false;
    program_->attach(op);
    const master::OpRunResult result = master::run_to_op(*master_, op);
    if (!result.ok()) throw std::runtime_error("line did not run in Op: " + result.error);
    task_.emplace(master_->transport(), result.layout, products_.size(), cycle, result.reference_station);
    task_->on_outputs(op.outputs);
    task_->on_inputs(op.inputs);
    cycle_ = cycle;
    next_ = clock_.now();
  }

  // One bus cycle from the current cycle start: the frame, then every timer up to the next start.
  // Returns false when an LRW working counter was wrong or a frame was lost.
  bool cycle() {
    advance_to(next_);
    const bool ok = task_->run_cycle();
    next_ += cycle_;
    advance_to(next_);
    return ok;
  }

  // Every drive enabled and not faulted (the program's view from the last cycles).
  bool drives_enabled() const {
    return std::all_of(program_->results().begin(), program_->results().end(),
                       [](const master::DriveResult& r) { return r.enabled && !r.faulted; });
  }

  const master::CyclicStats& stats() const { return task_->stats(); }
  const runtime::LoopCounters& counters() const { return counters_; }
  VirtualClock& clock() { return clock_; }
  network::Network& network() { return network_; }

private:
  void advance_to(Nanos t) { runtime::run_until(network_, *ends_.second, clock_, t, counters_); }

  std::vector<std::string> products_;
  VirtualClock clock_;
  network::Network network_;
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_;
  runtime::LoopCounters counters_;
  std::unique_ptr<master::Master> master_;
  std::unique_ptr<master::SineProgram> program_;
  std::optional<master::CyclicTask> task_;
  Nanos cycle_ = 0;
  Nanos next_ = 0;
};

}  // namespace vdrive::bench
