#pragma once
// ImpairedLink: a real link (the one `vdrive run` serves) with a WireImpairment between it and
// the line, in real time. Frames received from the master pass the to_slaves stage before the
// event loop sees them; replies sent back pass the to_master stage. Held frames (delay,
// reorder) come out at their time: receive() never waits past the next release, and sends due
// replies whenever it runs. A frame corrupted to_slaves goes to Segment::process_corrupted()
// (the ESCs count it) and is not returned. Like the inner link, receive() returns 0 early when
// its wait is interrupted by a signal (stop, runtime::LoopWaker).
//
// With a clean wire and nothing held, receive() and send() are the inner link's after one
// branch on a cached flag. Whoever changes the impairment's settings (FaultInjector, via the
// control service) calls refresh() afterwards. Nothing allocates per frame. Single-threaded:
// the event loop's thread. A frame still held for reorder when its setting is cleared while
// other wire faults stay active waits for the next frame (WireImpairment keeps it).
#include <array>

#include "common/clock.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/link.hpp"

namespace vdrive::network { class Network; }

namespace vdrive::fault {

class ImpairedLink final : public link::Link {
public:
  ImpairedLink(link::Link& inner, WireImpairment& wire, network::Network& network, const Clock& clock);

  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override;
  bool send(std::span<const std::uint8_t> frame) override;
  int fd() const override { return inner_.fd(); }
  // The inner link's while the wire is clean; while it holds or changes frames, a frame's
  // arrival is the impairment's to decide, so nothing may overtake: Unsupported.
  link::PeekCost peek_cost() const override { return engaged_ ? link::PeekCost::Unsupported : inner_.peek_cost(); }
  bool frame_waiting() override { return !engaged_ && inner_.frame_waiting(); }

  // Re-reads the impairment's settings: call after changing them.
  void refresh();
  // When the next held frame (either direction) comes out; INT64_MAX if none is held. Someone
  // who waits elsewhere (the scenario runner's real-time wire) must be back by then.
  Nanos next_release() const;
  bool engaged() const { return engaged_; }

private:
  std::size_t receive_impaired(std::span<std::uint8_t> buf, Nanos timeout);
  void send_due(Nanos now);
  // Next due to_slaves frame into `buf` (corrupted ones to the segment); 0 if none.
  std::size_t pop_due(std::span<std::uint8_t> buf, Nanos now);

  link::Link& inner_;
  WireImpairment& wire_;
  network::Network& network_;
  const Clock& clock_;
  bool engaged_ = false;
  std::array<std::uint8_t, link::kMaxFrame> scratch_{};
};

}  // namespace vdrive::fault
