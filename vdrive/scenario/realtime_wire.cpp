#include "vdrive/scenario/realtime_wire.hpp"

#include <poll.h>
#include <sys/prctl.h>

#include <algorithm>
#include <ctime>
#include <limits>

#include "vdrive/scenario/pcapng_writer.hpp"

namespace vdrive::scenario {
namespace {
constexpr Nanos kNever = std::numeric_limits<Nanos>::max();
constexpr Nanos kMaxWait = 10'000'000;
}  // namespace

RealtimeWire::RealtimeWire(network::Network& network, const Clock& clock, fault::WireImpairment& impairment,
                           link::Link* master, link::Link& line)
    : network_(network), clock_(clock), wire_(impairment), master_(master), line_(line) {
  // Timed waits end at SYNC deadlines: no 50 us timer slack (as runtime::serve does).
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
}

bool RealtimeWire::send(std::span<const std::uint8_t> frame) {
  if (!master_) return false;
  if (capture_) capture_->write(frame, clock_.now(), false);
  return master_->send(frame);
}

void RealtimeWire::release_due(Nanos now) {
  for (;;) {
    bool fcs_error = false;
    const std::size_t n = wire_.pop(fault::Direction::to_slaves, scratch_, now, fcs_error);
    if (n == 0) break;
    const std::span<std::uint8_t> frame = std::span(scratch_).first(n);
    if (fcs_error) {
      network_.segment().process_corrupted(frame, now);
      continue;
    }
    ++frames_;
    // As the event loop does: the frame goes back before the firmware reacts to it.
    if (network_.forward_frame(frame, now)) wire_.push(fault::Direction::to_master, frame, now);
    network_.service_irqs(now);
  }
  while (const std::size_t n = wire_.pop(fault::Direction::to_master, scratch_, now))
    line_.send(std::span<const std::uint8_t>(scratch_).first(n));
}

bool RealtimeWire::serve_once(Nanos until) {
  Nanos now = clock_.now();
  while (const std::size_t n = line_.receive(scratch_, 0)) wire_.push(fault::Direction::to_slaves, std::span(scratch_).first(n), now);
  release_due(now);
  if (network_.next_deadline() <= now) {
    network_.tick(now);
    release_due(clock_.now());
  }
  now = clock_.now();
  const Nanos next = std::min({until, network_.next_deadline(), wire_.next_release(fault::Direction::to_slaves),
                               wire_.next_release(fault::Direction::to_master)});
  const Nanos wait = next == kNever ? kMaxWait : std::clamp<Nanos>(next - now, 0, kMaxWait);
  pollfd fds[2] = {{line_.fd(), POLLIN, 0}, {master_ ? master_->fd() : -1, POLLIN, 0}};
  const timespec ts{static_cast<time_t>(wait / 1'000'000'000), static_cast<long>(wait % 1'000'000'000)};
  ::ppoll(fds, master_ ? 2 : 1, &ts, nullptr);
  return master_ && (fds[1].revents & POLLIN);
}

std::size_t RealtimeWire::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  const Nanos deadline = clock_.now() + std::max<Nanos>(timeout, 0);
  for (;;) {
    if (master_) {
      if (const std::size_t n = master_->receive(buf, 0)) {
        if (capture_) capture_->write(buf.first(n), clock_.now(), true);
        return n;
      }
    }
    if (clock_.now() >= deadline) return 0;
    serve_once(deadline);
  }
}

void RealtimeWire::serve_until(Nanos until) {
  while (clock_.now() < until) {
    if (serve_once(until) && master_) master_->receive(scratch_, 0);  // a late reply: nobody waits for it
  }
}

}  // namespace vdrive::scenario
