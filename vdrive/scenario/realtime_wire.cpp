#include "vdrive/scenario/realtime_wire.hpp"

#include <sys/prctl.h>

#include <algorithm>

#include "vdrive/scenario/pcapng_writer.hpp"

namespace vdrive::scenario {

RealtimeWire::RealtimeWire(network::Network& network, const Clock& clock, fault::WireImpairment& impairment,
                           link::Link* master, link::Link& line)
    : network_(network), clock_(clock), master_(master), line_(line, impairment, network, clock) {
  // Timed waits end at SYNC deadlines: no 50 us timer slack (as runtime::serve does).
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
}

bool RealtimeWire::send(std::span<const std::uint8_t> frame) {
  if (!master_) return false;
  if (capture_) capture_->write(frame, clock_.now(), false);
  return master_->send(frame);
}

Nanos RealtimeWire::serve_round(Nanos until) {
  const std::uint64_t sent = counters_.frames_out.load(std::memory_order_relaxed);
  line_.refresh();  // the runner's FaultInjector may have changed the wire between rounds
  runtime::serve_once(network_, *served_, clock_, until, counters_, service_);
  if (!master_ || counters_.frames_out.load(std::memory_order_relaxed) == sent) return 0;
  const Nanos back = std::min({network_.next_deadline(), line_.next_release(), until});
  return std::clamp(back - clock_.now(), Nanos{0}, runtime::kMaxWait);
}

std::size_t RealtimeWire::take_reply(std::span<std::uint8_t> buf, Nanos wait) {
  const std::size_t n = master_->receive(buf, wait);
  if (n != 0 && capture_) capture_->write(buf.first(n), clock_.now(), true);
  return n;
}

std::size_t RealtimeWire::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  const Nanos deadline = clock_.now() + std::max<Nanos>(timeout, 0);
  Nanos pickup = 0;
  for (;;) {
    if (master_) {
      if (const std::size_t n = take_reply(buf, pickup)) return n;
    }
    if (clock_.now() >= deadline) return catch_up(buf, deadline);
    pickup = serve_round(deadline);
  }
}

std::size_t RealtimeWire::catch_up(std::span<std::uint8_t> buf, Nanos deadline) {
  if (!master_) return 0;
  const Nanos held = line_.next_release();
  if (held > deadline && held <= clock_.now()) return 0;  // held past the deadline: truly late
  // Held frames come out inside the round without passing the loop's counters.
  const bool release_owed = held <= deadline;
  const std::uint64_t sent = counters_.frames_out.load(std::memory_order_relaxed);
  serve_round(deadline);
  if (!release_owed && counters_.frames_out.load(std::memory_order_relaxed) == sent) return 0;
  return take_reply(buf, kHandover);
}

void RealtimeWire::serve_until(Nanos until) {
  while (clock_.now() < until) {
    serve_round(until);
    if (master_) master_->receive(scratch_, 0);  // a late reply: nobody waits for it
  }
}

}  // namespace vdrive::scenario
