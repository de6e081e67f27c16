// A real link with a bad cable in it. See impaired_link.hpp.
#include "vdrive/fault/impaired_link.hpp"

#include <algorithm>
#include <limits>

#include "vdrive/network/network.hpp"

namespace vdrive::fault {
namespace {

constexpr Nanos kNever = std::numeric_limits<Nanos>::max();

bool clean(const WireSettings& s) {
  return s.drop == 0 && s.corrupt == 0 && s.duplicate == 0 && s.reorder == 0 && s.delay == 0;
}

}  // namespace

ImpairedLink::ImpairedLink(link::Link& inner, WireImpairment& wire, network::Network& network, const Clock& clock)
    : inner_(inner), wire_(wire), network_(network), clock_(clock) {
  refresh();
}

void ImpairedLink::refresh() {
  engaged_ = !clean(wire_.settings(Direction::to_slaves)) || !clean(wire_.settings(Direction::to_master)) ||
             next_release() != kNever;
}

Nanos ImpairedLink::next_release() const {
  return std::min(wire_.next_release(Direction::to_slaves), wire_.next_release(Direction::to_master));
}

std::size_t ImpairedLink::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  if (!engaged_) return inner_.receive(buf, timeout);
  const std::size_t n = receive_impaired(buf, timeout);
  refresh();  // the last held frame may just have left
  return n;
}

bool ImpairedLink::send(std::span<const std::uint8_t> frame) {
  if (!engaged_) return inner_.send(frame);
  const Nanos now = clock_.now();
  wire_.push(Direction::to_master, frame, now);
  send_due(now);
  refresh();
  return true;  // on the cable now; what happens to it there is the impairment's
}

void ImpairedLink::send_due(Nanos now) {
  while (const std::size_t n = wire_.pop(Direction::to_master, scratch_, now))
    inner_.send(std::span<const std::uint8_t>(scratch_).first(n));
}

std::size_t ImpairedLink::pop_due(std::span<std::uint8_t> buf, Nanos now) {
  for (;;) {
    bool fcs_error = false;
    const std::size_t n = wire_.pop(Direction::to_slaves, buf, now, fcs_error);
    if (n == 0 || !fcs_error) return n;
    network_.segment().process_corrupted(buf.first(n), now);
  }
}

std::size_t ImpairedLink::receive_impaired(std::span<std::uint8_t> buf, Nanos timeout) {
  const Nanos start = clock_.now();
  const Nanos deadline = timeout < 0 ? kNever : start + timeout;
  bool asked = false;  // the inner link was asked at least once (timeout 0 is one poll)
  for (;;) {
    const Nanos now = clock_.now();
    send_due(now);
    if (const std::size_t n = pop_due(buf, now)) return n;
    if (asked && now >= deadline) return 0;
    const Nanos next = std::min(deadline, next_release());
    const Nanos wait = next == kNever ? -1 : std::max<Nanos>(next - now, 0);
    const std::size_t n = inner_.receive(buf, wait);
    asked = true;
    if (n != 0) {
      wire_.push(Direction::to_slaves, buf.first(n), clock_.now());
    } else if (wait > 0 && clock_.now() < now + wait) {
      return 0;  // interrupted (a stop or wake-up signal): let the caller look at its flags
    }
  }
}

}  // namespace vdrive::fault
