#pragma once
// A Link for master unit tests: every sent frame goes to a responder that edits it into the reply
// (or drops it); receive() hands replies back in order. Time is a VirtualClock that receive()
// advances: by `round_trip` for a reply, by the whole timeout when nothing is queued.
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"

namespace vdrive::master::test {

class ScriptedLink final : public link::Link {
public:
  // Returns false to drop the frame (no reply).
  using Responder = std::function<bool(std::vector<std::uint8_t>& frame)>;

  ScriptedLink(VirtualClock& clock, Responder responder) : clock_(clock), responder_(std::move(responder)) {}

  bool send(std::span<const std::uint8_t> frame) override {
    sent.emplace_back(frame.begin(), frame.end());
    std::vector<std::uint8_t> reply(frame.begin(), frame.end());
    if (responder_(reply)) queue_.push_back(std::move(reply));
    return true;
  }

  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    if (queue_.empty()) {
      clock_.advance(timeout > 0 ? timeout : 0);
      return 0;
    }
    clock_.advance(round_trip);
    auto frame = std::move(queue_.front());
    queue_.pop_front();
    std::copy(frame.begin(), frame.end(), buf.begin());
    return frame.size();
  }

  // Queues a frame as if it had arrived unasked (late duplicate, foreign traffic).
  void inject(std::vector<std::uint8_t> frame) { queue_.push_back(std::move(frame)); }

  std::vector<std::vector<std::uint8_t>> sent;
  Nanos round_trip = 10'000;

private:
  VirtualClock& clock_;
  Responder responder_;
  std::deque<std::vector<std::uint8_t>> queue_;
};

}  // namespace vdrive::master::test
