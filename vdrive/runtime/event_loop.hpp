#pragma once
// The event loop: one thread owns a Network and a Link. It receives a frame (waiting at most
// until the next timer deadline), runs it through the line, sends the reply, then runs due
// timers. In real time a frame that arrives while the firmware runs overtakes it
// (frame_overtake.hpp). No locks, no allocation; the counters are single-writer atomics so
// another thread (a status line) may read them. A round that finds the line's timers late beyond
// a threshold records a host stall (LoopCounters::stalls, host_stalls.hpp).
//
// With batched control steps (Network::set_control_step_batch) the loop wakes for the bus, not for
// each step: every round first catches the drives up, and the frame's interrupts do so again.
//
// serve() runs in real time until `stop` is set; run_until() is the same loop in virtual time
// for tests and scenarios: it handles every frame already waiting and jumps the VirtualClock from
// deadline to deadline.
#include <atomic>
#include <cstdint>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/runtime/loop_counters.hpp"
#include "vdrive/runtime/loop_service.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::runtime {

// Longest single wait in serve(), so a stop request is noticed even if no signal interrupts the
// wait and no timer is due.
constexpr Nanos kMaxWait = 10'000'000;

// Serves until `stop` becomes true (checked at least every kMaxWait). An exception from the
// link (LinkError: its interface was removed) ends serving and propagates. Sets the calling
// thread's timer slack to 1 ns so timed waits end on the deadline, not up to 50 us later.
// `service` (optional) is polled once per iteration and its deadline joins the network's.
void serve(network::Network& network, link::Link& link, const Clock& clock,
           const std::atomic<bool>& stop, LoopCounters& counters, LoopService* service = nullptr);

// One round of serve(): the service's poll, due timers, then one wait on the link (until the next
// deadline, `until` at the latest, kMaxWait at most) and the frame it brings. For a thread that
// serves a line between other work (the scenario runner's real-time wire); serve() is this in a
// loop with no `until`.
void serve_once(network::Network& network, link::Link& link, const Clock& clock, Nanos until,
                LoopCounters& counters, LoopService* service = nullptr);

// Virtual time: handles waiting frames and due timers, advancing `clock` to each deadline up to
// `until`; returns idle, with the clock at `until` (never moved backwards). Throws
// std::logic_error if a timer keeps firing at one instant without its deadline moving on.
void run_until(network::Network& network, link::Link& link, VirtualClock& clock, Nanos until,
               LoopCounters& counters);

// run_until(clock.now()): everything that is pending now, without advancing time.
void run_pending(network::Network& network, link::Link& link, VirtualClock& clock,
                 LoopCounters& counters);

}  // namespace vdrive::runtime
