#include "vdrive/runtime/frame_overtake.hpp"

namespace vdrive::runtime {

void pass_frame(network::Network& network, link::Link& link, std::span<std::uint8_t> frame, Nanos now,
                LoopCounters& counters) {
  bump(counters.frames_in);
  switch (network.forward_frame(frame, now)) {
    case network::FrameExit::Destroyed: bump(counters.dropped); break;
    case network::FrameExit::ToMaster: bump(link.send(frame) ? counters.frames_out : counters.send_failed); break;
    case network::FrameExit::Onward: bump(link.send_onward(frame) ? counters.onward : counters.send_failed); break;
  }
}

FrameOvertake::FrameOvertake(network::Network& network, link::Link& link, const Clock& clock,
                             LoopCounters& counters, Nanos now)
    : network_(network),
      link_(link),
      clock_(clock),
      counters_(counters),
      cost_(link.peek_cost()),
      next_peek_(now + kSyscallPeekInterval) {}

void FrameOvertake::run() {
  if (cost_ == link::PeekCost::SystemCall) {
    const Nanos now = clock_.now();
    if (now < next_peek_) return;
    next_peek_ = now + kSyscallPeekInterval;
  }
  take_waiting();
}

// A system-call peek costs as much as a non-blocking receive, so those links are simply asked
// for a frame; a free peek is made first, so an empty link costs one load.
void FrameOvertake::take_waiting() {
  if (cost_ == link::PeekCost::Unsupported) return;
  for (int i = 0; i < kMaxFramesInOneGo; ++i) {
    if (cost_ == link::PeekCost::Free && !link_.frame_waiting()) return;
    const std::size_t n = link_.receive(buf_, 0);
    if (n == 0) return;
    pass_frame(network_, link_, std::span(buf_).first(n), clock_.now(), counters_);
    irqs_owed_ = true;
  }
}

void FrameOvertake::serve_frame(std::size_t length, Nanos now) {
  pass_frame(network_, link_, std::span(buf_).first(length), now, counters_);
  take_waiting();
  irqs_owed_ = false;  // the pass below services what the frames above raised
  network_.service_irqs(now, hook());
  service_owed_irqs();
}

void FrameOvertake::service_owed_irqs() {
  if (!irqs_owed_) return;
  irqs_owed_ = false;
  network_.service_irqs(clock_.now());
}

}  // namespace vdrive::runtime
