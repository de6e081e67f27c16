#pragma once
// OnwardLink: the master's link with the line's onward port beside it, for a line that goes on
// beyond this process (`vdrive run --next-iface`; docs/scale-out.md). To the event loop it is the
// master's link: receive() returns the master's frames and send() answers the master; a frame the
// segment routes onward (network::FrameExit::Onward) leaves through send_onward() on the onward
// link. Frames coming back on the onward link are handled inside receive() and frame_waiting(),
// whatever the loop waits for: they pass the segment's way back (Network::return_frame, the DC
// receive-time latches) and go straight out to the master, as the silicon forwards a frame from
// port 1 to port 0 without waiting for anyone.
//
// The onward link's carrier is read at most every kCarrierInterval and becomes the onward port's
// link (Segment::set_onward_link): with nothing cabled beyond (the peer down, the cable out) the
// last slave closes its port 1 and the line ends there, as loop control does on the silicon.
// A peer that has link but does not answer loses the frames, as a broken slave would. An onward
// interface that disappears (its receive throws LinkError) is a link down for good: the line ends
// at the last slave here and the run goes on serving the master.
//
// The master's link may be a wrapper (the wire-fault stage, telemetry's timing); when it cannot
// say whether a frame waits (peek Unsupported: the wire fault holds frames), a wait is cut into
// kHeldFrameSlice pieces so held frames still come out near their time. Loop thread only; nothing
// allocates after construction; a signal (stop, LoopWaker) ends a wait early, as the links' do.
#include <array>
#include <cstdint>
#include <span>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/loop_counters.hpp"

namespace vdrive::runtime {

constexpr Nanos kCarrierInterval = 10'000'000;
constexpr Nanos kHeldFrameSlice = 50'000;

class OnwardLink final : public link::Link {
public:
  // `master` and `onward` need pollable fds. Reads the onward carrier once now.
  OnwardLink(link::Link& master, link::Link& onward, network::Network& network, const Clock& clock,
             LoopCounters& counters);

  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override;
  bool send(std::span<const std::uint8_t> frame) override { return master_.send(frame); }
  bool send_onward(std::span<const std::uint8_t> frame) override { return onward_.send(frame); }
  link::PeekCost peek_cost() const override { return master_.peek_cost(); }
  // Passes the frames that came back first (when the onward link can tell cheaply).
  bool frame_waiting() override;
  int fd() const override { return master_.fd(); }
  bool carrier() override { return master_.carrier(); }

private:
  void check_carrier(Nanos now);
  // Every frame waiting on the onward link, back to the master (a bounded number per call).
  void take_returns();

  link::Link& master_;
  link::Link& onward_;
  network::Network& network_;
  const Clock& clock_;
  LoopCounters& counters_;
  Nanos next_carrier_check_ = 0;
  bool gone_ = false;  // the onward interface was removed
  std::array<std::uint8_t, link::kMaxFrame> returning_{};
};

}  // namespace vdrive::runtime
