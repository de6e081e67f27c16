#pragma once
// A line of vdrive slaves for master tests, in virtual time, wired as the program wires it: the
// master's LoopbackLink endpoint on one side, the network's endpoint served by the event loop
// (runtime::run_until) on the other. The master sees a Link whose receive() runs the event loop
// for the wire round trip, then for as long as the master is willing to wait.
#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::master::test {

class VirtualLine final : public link::Link {
public:
  // Wire time of one round trip for a frame of typical size at 100 Mbit/s (there and back).
  static constexpr Nanos kRoundTrip = 20'000;

  explicit VirtualLine(std::vector<std::string> products, const network::NetworkOptions& options = {})
      : products_(std::move(products)), network_(products_, clock_, options), ends_(link::make_loopback_pair()) {}

  bool send(std::span<const std::uint8_t> frame) override { return ends_.first->send(frame); }

  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    const Nanos start = clock_.now();
    runtime::run_until(network_, *ends_.second, clock_, start + std::min<Nanos>(kRoundTrip, std::max<Nanos>(timeout, 0)),
                       counters_);
    if (after_run) after_run();
    if (const std::size_t n = take(buf)) return n;
    runtime::run_until(network_, *ends_.second, clock_, start + std::max<Nanos>(timeout, 0), counters_);
    if (after_run) after_run();
    return take(buf);
  }

  // Test hooks: work done after the network ran (a stand-in firmware), and replies to lose.
  std::function<void()> after_run;
  std::function<bool(std::span<const std::uint8_t>)> drop_reply;

  VirtualClock& clock() { return clock_; }
  network::Network& network() { return network_; }
  const runtime::LoopCounters& counters() const { return counters_; }

private:
  std::size_t take(std::span<std::uint8_t> buf) {
    for (;;) {
      const std::size_t n = ends_.first->receive(buf, 0);
      if (n == 0 || !drop_reply || !drop_reply(buf.first(n))) return n;
    }
  }

  std::vector<std::string> products_;
  VirtualClock clock_;
  network::Network network_;
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_;
  runtime::LoopCounters counters_;
};

}  // namespace vdrive::master::test
