#pragma once
// The scenario runner's wire in real time, on one thread: the line of slaves served on a real
// interface (`line`), and, for the built-in master, the master's own interface (`master`, e.g.
// the other end of a veth pair). While the master waits for a reply, receive() serves the line:
// frames from the line's socket pass the to_slaves impairment stage into the Network (corrupted
// ones to Segment::process_corrupted), replies pass the to_master stage back out, and the
// Network's timers (SYNC, watchdogs, firmware) run at their deadlines on the monotonic clock.
// With no built-in master (`master` null) an external master drives the line and serve_until()
// is all the runner calls. Nothing allocates per frame; expectations read the drives on this
// same thread, so no locks are needed.
#include <array>
#include <cstdint>

#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/scenario/scenario_wire.hpp"

namespace vdrive::scenario {

class RealtimeWire final : public ScenarioWire {
public:
  RealtimeWire(network::Network& network, const Clock& clock, fault::WireImpairment& impairment, link::Link* master,
               link::Link& line);

  bool send(std::span<const std::uint8_t> frame) override;
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override;
  void set_capture(PcapngWriter* capture) override { capture_ = capture; }
  void serve_until(Nanos until) override;

  std::uint64_t frames_served() const { return frames_; }

private:
  // One round: due impairment releases, frames waiting on the line's socket, due timers; then
  // waits (both sockets) until something is due or `until`. Returns true if a frame for the
  // built-in master is waiting.
  bool serve_once(Nanos until);
  void release_due(Nanos now);

  network::Network& network_;
  const Clock& clock_;
  fault::WireImpairment& wire_;
  link::Link* master_;
  link::Link& line_;
  PcapngWriter* capture_ = nullptr;
  std::array<std::uint8_t, link::kMaxFrame> scratch_{};
  std::uint64_t frames_ = 0;
};

}  // namespace vdrive::scenario
