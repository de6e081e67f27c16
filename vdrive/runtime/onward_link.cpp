#include "vdrive/runtime/onward_link.hpp"

#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <ctime>
#include <limits>
#include <stdexcept>

#include "vdrive/link/link_error.hpp"
#include "vdrive/runtime/frame_overtake.hpp"

namespace vdrive::runtime {
namespace {

constexpr Nanos kNever = std::numeric_limits<Nanos>::max();

}  // namespace

OnwardLink::OnwardLink(link::Link& master, link::Link& onward, network::Network& network, const Clock& clock,
                       LoopCounters& counters)
    : master_(master), onward_(onward), network_(network), clock_(clock), counters_(counters) {
  if (master.fd() < 0 || onward.fd() < 0) throw std::invalid_argument("an onward port needs links with file descriptors");
  counters.has_onward.store(true, std::memory_order_relaxed);
  check_carrier(clock.now());
}

void OnwardLink::check_carrier(Nanos now) {
  if (now < next_carrier_check_) return;
  next_carrier_check_ = now + kCarrierInterval;
  const bool up = !gone_ && onward_.carrier();
  if (up == network_.segment().onward_link()) return;
  network_.segment().set_onward_link(up);
  counters_.onward_link.store(up, std::memory_order_relaxed);
}

void OnwardLink::take_returns() {
  if (gone_) return;
  for (int i = 0; i < kMaxFramesInOneGo; ++i) {
    std::size_t n = 0;
    try {
      n = onward_.receive(returning_, 0);
    } catch (const link::LinkError&) {
      // The interface was removed (a USB NIC unplugged, the peer's veth deleted): the cable is
      // out for good, so the line ends at the last slave here. The master's link goes on.
      gone_ = true;
      next_carrier_check_ = 0;
      check_carrier(clock_.now());
      return;
    }
    if (n == 0) return;
    const std::span<std::uint8_t> frame = std::span(returning_).first(n);
    if (!network_.return_frame(frame, clock_.now())) continue;
    bump(counters_.returned);
    bump(master_.send(frame) ? counters_.frames_out : counters_.send_failed);
  }
}

bool OnwardLink::frame_waiting() {
  if (!gone_ && onward_.peek_cost() == link::PeekCost::Free && onward_.frame_waiting()) take_returns();
  return master_.frame_waiting();
}

std::size_t OnwardLink::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  const Nanos start = clock_.now();
  check_carrier(start);
  take_returns();
  if (timeout == 0) return master_.receive(buf, 0);
  const Nanos until = timeout < 0 ? kNever : start + timeout;
  for (;;) {
    if (master_.peek_cost() == link::PeekCost::Free && master_.frame_waiting()) {
      if (const std::size_t n = master_.receive(buf, 0)) return n;
    }
    const bool held = master_.peek_cost() == link::PeekCost::Unsupported;
    const Nanos now = clock_.now();
    if (now >= until) return master_.receive(buf, 0);
    Nanos wait = std::min(until - now, kCarrierInterval);
    if (held) wait = std::min(wait, kHeldFrameSlice);
    const timespec ts{static_cast<time_t>(wait / 1'000'000'000), static_cast<long>(wait % 1'000'000'000)};
    pollfd fds[2] = {{master_.fd(), POLLIN, 0}, {gone_ ? -1 : onward_.fd(), POLLIN, 0}};  // -1: not polled
    const int ready = ::ppoll(fds, 2, &ts, nullptr);
    if (ready < 0) return 0;  // a signal: the caller looks at its stop flag and wakers
    if (fds[1].revents != 0) take_returns();
    // Errors (an interface removed) surface from the link's own receive(), which throws.
    if (fds[0].revents != 0 || (held && ready == 0)) {
      if (const std::size_t n = master_.receive(buf, 0)) return n;
    }
    check_carrier(clock_.now());
  }
}

}  // namespace vdrive::runtime
