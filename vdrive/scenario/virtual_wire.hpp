#pragma once
// The built-in master's Link in virtual time: the cable between the master and slave 1, with a
// fault::WireImpairment stage in each direction, into a Network served by the event loop
// (runtime::run_until) on the other end of an in-process loopback pair.
//  - send(): the frame enters the to_slaves stage at the current time;
//  - receive(): lets the line run (the clock jumps from deadline to deadline) until a reply comes
//    out of the to_master stage or the timeout passes. A reply leaves the line kWireTime after its
//    frame went in (two 100 Mbit/s wire times of a typical frame). Corrupted frames to the slaves
//    go to Segment::process_corrupted (the ESCs count them); corrupted replies are lost.
// Frames the master sends and receives are written to the capture, if one is set, as a capture
// on the master's port would show them.
#include <cstdint>
#include <memory>
#include <span>
#include <utility>

#include "common/clock.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/scenario/scenario_wire.hpp"

namespace vdrive::scenario {

class VirtualWire final : public ScenarioWire {
public:
  static constexpr Nanos kWireTime = 20'000;

  VirtualWire(network::Network& network, VirtualClock& clock, fault::WireImpairment& impairment);

  bool send(std::span<const std::uint8_t> frame) override;
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override;

  void set_capture(PcapngWriter* capture) override { capture_ = capture; }
  void serve_until(Nanos until) override;
  const runtime::LoopCounters& counters() const { return counters_; }

private:
  // Moves frames due on the to_slaves stage into the line and the replies into to_master.
  void deliver();

  network::Network& network_;
  VirtualClock& clock_;
  fault::WireImpairment& wire_;
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_;
  runtime::LoopCounters counters_;
  PcapngWriter* capture_ = nullptr;
  std::array<std::uint8_t, link::kMaxFrame> scratch_{};
};

}  // namespace vdrive::scenario
