#include "vdrive/scenario/virtual_wire.hpp"

#include <algorithm>

#include "vdrive/scenario/pcapng_writer.hpp"

namespace vdrive::scenario {

VirtualWire::VirtualWire(network::Network& network, VirtualClock& clock, fault::WireImpairment& impairment)
    : network_(network), clock_(clock), wire_(impairment), ends_(link::make_loopback_pair()) {}

bool VirtualWire::send(std::span<const std::uint8_t> frame) {
  if (capture_) capture_->write(frame, clock_.now(), false);
  wire_.push(fault::Direction::to_slaves, frame, clock_.now());
  return true;
}

void VirtualWire::deliver() {
  const Nanos now = clock_.now();
  bool sent = false;
  for (;;) {
    bool fcs_error = false;
    const std::size_t n = wire_.pop(fault::Direction::to_slaves, scratch_, now, fcs_error);
    if (n == 0) break;
    if (fcs_error) {
      network_.segment().process_corrupted(std::span(scratch_).first(n), now);
    } else {
      ends_.first->send(std::span<const std::uint8_t>(scratch_).first(n));
      sent = true;
    }
  }
  if (!sent) return;
  runtime::run_pending(network_, *ends_.second, clock_, counters_);
  while (const std::size_t n = ends_.first->receive(scratch_, 0))
    wire_.push(fault::Direction::to_master, std::span<const std::uint8_t>(scratch_).first(n), now + kWireTime);
}

std::size_t VirtualWire::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  const Nanos deadline = clock_.now() + std::max<Nanos>(timeout, 0);
  for (;;) {
    deliver();
    if (const std::size_t n = wire_.pop(fault::Direction::to_master, buf, clock_.now())) {
      if (capture_) capture_->write(buf.first(n), clock_.now(), true);
      return n;
    }
    if (clock_.now() >= deadline) return 0;
    const Nanos next = std::min({deadline, wire_.next_release(fault::Direction::to_slaves),
                                 wire_.next_release(fault::Direction::to_master)});
    // At least 1 ns per round, so a stage that reports a due frame it does not give out cannot spin.
    runtime::run_until(network_, *ends_.second, clock_, std::max(next, clock_.now() + 1), counters_);
    // Replies the line sent while time passed (none expected: every frame is answered in deliver()).
    while (const std::size_t n = ends_.first->receive(scratch_, 0))
      wire_.push(fault::Direction::to_master, std::span<const std::uint8_t>(scratch_).first(n), clock_.now() + kWireTime);
  }
}

}  // namespace vdrive::scenario

namespace vdrive::scenario {

void VirtualWire::serve_until(Nanos until) {
  std::array<std::uint8_t, link::kMaxFrame> buf{};
  while (clock_.now() < until) receive(buf, until - clock_.now());
}

}  // namespace vdrive::scenario
