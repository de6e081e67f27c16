#pragma once
// TimedLink: a Link that passes frames through to another and measures, for the telemetry's
// bus state, how long the event loop took from a frame's arrival (receive() returning it) to
// its reply leaving (send()). Loop thread only; two clock reads per frame, no allocation.
#include "vdrive/link/link.hpp"
#include "vdrive/telemetry/turnaround.hpp"

namespace vdrive::telemetry {

class TimedLink final : public link::Link {
public:
  TimedLink(link::Link& inner, const Clock& clock, TurnaroundStats& stats) : inner_(inner), clock_(clock), stats_(stats) {}

  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override {
    const std::size_t n = inner_.receive(buf, timeout);
    if (n != 0) received_ = clock_.now();
    return n;
  }
  bool send(std::span<const std::uint8_t> frame) override {
    const bool sent = inner_.send(frame);
    if (sent && received_ >= 0) stats_.add(clock_.now() - received_);
    received_ = -1;  // a frame the link sends on its own (none today) has no turnaround
    return sent;
  }
  int fd() const override { return inner_.fd(); }
  link::PeekCost peek_cost() const override { return inner_.peek_cost(); }
  bool frame_waiting() override { return inner_.frame_waiting(); }

private:
  link::Link& inner_;
  const Clock& clock_;
  TurnaroundStats& stats_;
  Nanos received_ = -1;
};

}  // namespace vdrive::telemetry
