#include "vdrive/runtime/event_loop.hpp"

#include <sys/prctl.h>

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>

#include "vdrive/runtime/frame_overtake.hpp"

namespace vdrive::runtime {
namespace {

constexpr Nanos kNever = std::numeric_limits<Nanos>::max();
// More timer runs than this at one instant means a deadline that never moves on: a bug, not load.
constexpr int kMaxTicksPerInstant = 100'000;

using FrameBuffer = std::array<std::uint8_t, link::kMaxFrame>;

void handle_frame(network::Network& network, link::Link& link, std::span<std::uint8_t> frame,
                  Nanos now, LoopCounters& counters) {
  pass_frame(network, link, frame, now, counters);
  // Even a destroyed frame may have changed ESC state before its error was found.
  network.service_irqs(now);
}

}  // namespace

void serve(network::Network& network, link::Link& link, const Clock& clock,
           const std::atomic<bool>& stop, LoopCounters& counters, LoopService* service) {
  // Timed waits end at SYNC/firmware deadlines (cycles down to 125 us); the default 50 us timer
  // slack of a normal thread would show as jitter there. 1 ns: wake when asked.
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  counters.stalls.restart();  // the time before serving is no stall
  while (!stop.load(std::memory_order_relaxed)) serve_once(network, link, clock, kNever, counters, service);
}

void serve_once(network::Network& network, link::Link& link, const Clock& clock, Nanos until,
                LoopCounters& counters, LoopService* service) {
  Nanos now = clock.now();
  counters.stalls.check(network, now);  // late for the timers planned last round: a host stall
  FrameOvertake overtake(network, link, clock, counters, now);
  // Batched control steps run at every wake, whatever woke the loop, so a service (a sample, a
  // fault, a web request) sees the drives as of now.
  if (network.control_step_batch() > 0) network.catch_up(now, overtake.hook());
  if (service != nullptr) service->poll(now);
  Nanos deadline = network.next_deadline();
  if (deadline <= now) {
    network.tick(now, overtake.hook());
    overtake.service_owed_irqs();
    deadline = network.next_deadline();
    now = clock.now();
    counters.stalls.check(network, now);  // time lost inside this round (a service, the firmware)
  }
  // The line's timers are what the drives see; the loop means to run them then (now if behind).
  counters.stalls.plan(deadline == kNever ? kNever : std::max(deadline, now));
  if (service != nullptr) deadline = std::min(deadline, service->next_deadline());
  deadline = std::min(deadline, until);
  const Nanos wait = deadline == kNever ? kMaxWait : std::clamp(deadline - now, Nanos{0}, kMaxWait);
  const std::size_t n = link.receive(overtake.buffer(), wait);
  if (n != 0) overtake.serve_frame(n, clock.now());
}

void run_until(network::Network& network, link::Link& link, VirtualClock& clock, Nanos until,
               LoopCounters& counters) {
  FrameBuffer buf;
  int ticks_at_this_instant = 0;
  for (;;) {
    while (const std::size_t n = link.receive(buf, 0)) {
      handle_frame(network, link, std::span(buf).first(n), clock.now(), counters);
    }
    const Nanos deadline = network.next_deadline();
    if (deadline > until) {
      if (clock.now() < until) clock.set(until);
      return;
    }
    if (deadline > clock.now()) {
      clock.set(deadline);
      ticks_at_this_instant = 0;
    } else if (++ticks_at_this_instant > kMaxTicksPerInstant) {
      throw std::logic_error("event loop: a timer due at " + std::to_string(deadline) +
                             " ns keeps firing without moving its deadline");
    }
    network.tick(clock.now());
  }
}

void run_pending(network::Network& network, link::Link& link, VirtualClock& clock,
                 LoopCounters& counters) {
  run_until(network, link, clock, clock.now(), counters);
}

}  // namespace vdrive::runtime
