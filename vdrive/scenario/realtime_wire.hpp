#pragma once
// The scenario runner's wire in real time, on one thread: the line of slaves served on a real
// interface (`line`), and, for the built-in master, the master's own interface (`master`, e.g.
// the other end of a veth pair). The line is served as `vdrive run` serves it: the event loop's
// round (runtime::serve_once) behind a fault::ImpairedLink, so wire faults act the same way in
// both. While the master waits for a reply, receive() serves the line; when a round sent a reply,
// it waits for it at the master's end (veth hands it over within microseconds), never past the
// line's next deadline or the wire's next held frame (a delayed reply comes out on time). With no built-in master (`master` null) an external master drives the
// line and serve_until() is all the runner calls. Nothing allocates per frame; expectations read
// the drives on this same thread, so no locks are needed.
#include <array>
#include <cstdint>

#include "vdrive/fault/impaired_link.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
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

  // The line as served (behind the wire's impairment) and its counters, for a LineTap to wrap;
  // attach() then serves through `served` and polls `service` every round.
  link::Link& line() { return line_; }
  const runtime::LoopCounters& counters() const { return counters_; }
  void attach(link::Link& served, runtime::LoopService* service) {
    served_ = &served;
    service_ = service;
  }

private:
  // One round of the line, `until` at the latest; returns how long to wait at the master's end
  // for a reply the round sent (0: none sent).
  Nanos serve_round(Nanos until);
  // The master's end: a reply within `wait` (captured if asked).
  std::size_t take_reply(std::span<std::uint8_t> buf, Nanos wait);
  // The wait ended with no reply. If the host kept this thread from running (it serves the line
  // and the master alike), the line did not get to answer in time, which a line of its own would
  // have: so what it owed by `deadline` — the answer to a frame waiting at its port, a reply a
  // wire fault held until then — is sent now and still counts. A reply held past the deadline
  // does not.
  std::size_t catch_up(std::span<std::uint8_t> buf, Nanos deadline);
  // A reply on veth reaches the other end within microseconds; this bounds the wait for it.
  static constexpr Nanos kHandover = 100'000;

  network::Network& network_;
  const Clock& clock_;
  link::Link* master_;
  fault::ImpairedLink line_;
  link::Link* served_ = &line_;
  runtime::LoopService* service_ = nullptr;
  runtime::LoopCounters counters_;
  PcapngWriter* capture_ = nullptr;
  std::array<std::uint8_t, link::kMaxFrame> scratch_{};
};

}  // namespace vdrive::scenario
