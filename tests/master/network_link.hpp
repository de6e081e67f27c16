#pragma once
// A Link straight into a vdrive Network in virtual time, for master tests: a sent frame is
// processed by the line when the master waits for it (after a wire round trip), and while the
// master waits the network's timers run at their deadlines, as the event loop would run them.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::master::test {

class NetworkLink final : public link::Link {
public:
  NetworkLink(network::Network& network, VirtualClock& clock) : network_(network), clock_(clock) {}

  bool send(std::span<const std::uint8_t> frame) override {
    if (frame.size() > pending_.size()) return false;
    std::memcpy(pending_.data(), frame.data(), frame.size());
    pending_size_ = frame.size();
    return true;
  }

  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    if (pending_size_ == 0) {
      run_timers_until(clock_.now() + std::max<Nanos>(timeout, 0));
      return 0;
    }
    const std::size_t n = pending_size_;
    pending_size_ = 0;
    // 100 Mbit/s: 80 ns per byte plus preamble/IFG, there and back.
    run_timers_until(clock_.now() + static_cast<Nanos>(n + 20) * 80);
    ++frames;
    if (!network_.process_frame({pending_.data(), n}, clock_.now())) return 0;
    run_timers_until(clock_.now() + static_cast<Nanos>(n + 20) * 80);
    std::memcpy(buf.data(), pending_.data(), n);
    return n;
  }

  std::uint64_t frames = 0;

private:
  void run_timers_until(Nanos until) {
    int same_instant = 0;
    for (Nanos due = network_.next_deadline(); due <= until; due = network_.next_deadline()) {
      if (due <= clock_.now() && ++same_instant > 1000) {
        throw std::logic_error("network timer does not move on");
      }
      clock_.set(std::max(due, clock_.now()));
      network_.tick(clock_.now());
    }
    clock_.set(until);
  }

  network::Network& network_;
  VirtualClock& clock_;
  std::array<std::uint8_t, link::kMaxFrame> pending_{};
  std::size_t pending_size_ = 0;
};

}  // namespace vdrive::master::test
