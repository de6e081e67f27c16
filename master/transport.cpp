#include "master/transport.hpp"

#include <algorithm>
#include <cstring>

namespace vdrive::master {

Transport::Transport(link::Link& link, const Clock& clock, TransportOptions options)
    : link_(link), clock_(clock), options_(options), frame_(options.source) {}

bool Transport::transceive(Frame& frame) {
  for (int attempt = 0; attempt <= options_.retries; ++attempt) {
    if (exchange(frame, options_.reply_timeout)) return true;
  }
  return false;
}

bool Transport::exchange(Frame& frame, Nanos timeout) { return exchange(std::span<Frame>(&frame, 1), timeout) == 1; }

std::uint64_t Transport::exchange(std::span<Frame> frames, Nanos timeout) {
  const std::size_t n = std::min<std::size_t>(frames.size(), 64);
  std::uint64_t waiting = 0;  // sent and not answered yet
  for (std::size_t i = 0; i < n; ++i) {
    if (link_.send(frames[i].bytes())) {
      ++frames_sent_;
      waiting |= std::uint64_t{1} << i;
    }
  }
  std::uint64_t answered = 0;
  const Nanos deadline = clock_.now() + timeout;
  while (waiting != 0) {
    const Nanos left = deadline - clock_.now();
    if (left <= 0) break;
    const Nanos before = clock_.now();
    const std::size_t len = link_.receive(rx_, left);
    if (len == 0) {
      // Nothing arrived. Under a virtual clock that the link did not advance, nothing will:
      // end this attempt instead of spinning.
      if (clock_.now() == before) break;
      continue;
    }
    // Anything else (a late reply to an earlier attempt, a duplicate, other masters' traffic) is
    // skipped: indexes differ, so a reply matches at most one waiting frame.
    const std::span<const std::uint8_t> reply(rx_.data(), len);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t bit = std::uint64_t{1} << i;
      if ((waiting & bit) != 0 && frames[i].accept_reply(reply)) {
        waiting &= ~bit;
        answered |= bit;
        break;
      }
    }
  }
  if (answered != (n == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1)) ++timeouts_;
  return answered;
}

void Transport::idle_until(Nanos deadline) {
  for (;;) {
    const Nanos left = deadline - clock_.now();
    if (left <= 0) return;
    const Nanos before = clock_.now();
    if (link_.receive(rx_, left) == 0 && clock_.now() == before) return;  // a clock nobody moves
  }
}

Wkc Transport::single(Command cmd, std::uint32_t address, std::span<std::uint8_t> inout, bool send_data) {
  frame_.clear();
  const std::uint8_t idx = next_index();
  const int slot = send_data ? frame_.add(cmd, idx, address, std::span<const std::uint8_t>(inout))
                             : frame_.add(cmd, idx, address, static_cast<std::uint16_t>(inout.size()));
  if (slot < 0) return std::nullopt;
  if (!transceive(frame_)) return std::nullopt;
  const auto reply = frame_.data(static_cast<std::size_t>(slot));
  std::copy(reply.begin(), reply.end(), inout.begin());
  return frame_.wkc(static_cast<std::size_t>(slot));
}

namespace {
// Writes never change the caller's buffer; single() copies the reply back, so give it a copy.
template <class F> Wkc write_only(std::span<const std::uint8_t> data, F&& send) {
  std::array<std::uint8_t, Frame::kMaxFrameBytes> copy;
  if (data.size() > copy.size()) return std::nullopt;
  std::memcpy(copy.data(), data.data(), data.size());
  return send(std::span<std::uint8_t>(copy.data(), data.size()));
}
}  // namespace

Wkc Transport::aprd(std::uint16_t position, std::uint16_t ado, std::span<std::uint8_t> data) {
  return single(Command::APRD, position_address(position, ado), data, false);
}
Wkc Transport::apwr(std::uint16_t position, std::uint16_t ado, std::span<const std::uint8_t> data) {
  return write_only(data, [&](auto buf) { return single(Command::APWR, position_address(position, ado), buf, true); });
}
Wkc Transport::aprw(std::uint16_t position, std::uint16_t ado, std::span<std::uint8_t> data) {
  return single(Command::APRW, position_address(position, ado), data, true);
}
Wkc Transport::fprd(std::uint16_t station, std::uint16_t ado, std::span<std::uint8_t> data) {
  return single(Command::FPRD, station_address(station, ado), data, false);
}
Wkc Transport::fpwr(std::uint16_t station, std::uint16_t ado, std::span<const std::uint8_t> data) {
  return write_only(data, [&](auto buf) { return single(Command::FPWR, station_address(station, ado), buf, true); });
}
Wkc Transport::fprw(std::uint16_t station, std::uint16_t ado, std::span<std::uint8_t> data) {
  return single(Command::FPRW, station_address(station, ado), data, true);
}
Wkc Transport::brd(std::uint16_t ado, std::span<std::uint8_t> data) {
  return single(Command::BRD, station_address(0, ado), data, false);
}
Wkc Transport::bwr(std::uint16_t ado, std::span<const std::uint8_t> data) {
  return write_only(data, [&](auto buf) { return single(Command::BWR, station_address(0, ado), buf, true); });
}
Wkc Transport::lrd(std::uint32_t logical, std::span<std::uint8_t> data) {
  return single(Command::LRD, logical, data, false);
}
Wkc Transport::lwr(std::uint32_t logical, std::span<const std::uint8_t> data) {
  return write_only(data, [&](auto buf) { return single(Command::LWR, logical, buf, true); });
}
Wkc Transport::lrw(std::uint32_t logical, std::span<std::uint8_t> data) {
  return single(Command::LRW, logical, data, true);
}
Wkc Transport::armw(std::uint16_t position, std::uint16_t ado, std::span<std::uint8_t> data) {
  return single(Command::ARMW, position_address(position, ado), data, true);
}
Wkc Transport::frmw(std::uint16_t station, std::uint16_t ado, std::span<std::uint8_t> data) {
  return single(Command::FRMW, station_address(station, ado), data, true);
}

}  // namespace vdrive::master
