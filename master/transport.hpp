#pragma once
// Datagram transport over a Link: sends a frame, waits for the reply whose datagram indexes match
// (other frames are ignored), retries a bounded number of times on timeout, and offers one typed
// call per EtherCAT command. Every call returns the working counter, or std::nullopt when no
// reply came back after all retries (a broken link, not a slave refusing: that is WKC 0).
#include <cstdint>
#include <optional>
#include <span>

#include "common/clock.hpp"
#include "master/frame.hpp"
#include "vdrive/link/link.hpp"

namespace vdrive::master {

using Wkc = std::optional<std::uint16_t>;

struct TransportOptions {
  Nanos reply_timeout = 20'000'000;   // per attempt (20 ms: generous for veth and loaded hosts)
  int retries = 3;                    // further attempts after the first one times out
  MacAddress source = kDefaultMasterMac;
};

class Transport {
public:
  Transport(link::Link& link, const Clock& clock, TransportOptions options = {});

  // Sends `frame` and waits for its reply; on success the frame holds the reply (data(), wkc()).
  // Returns false when all attempts timed out or the link refused the frame.
  bool transceive(Frame& frame);
  // One attempt only, waiting at most `timeout` (cyclic process data: a lost frame is a wrong
  // working counter for that cycle, never a retry).
  bool exchange(Frame& frame, Nanos timeout);
  // The same for several frames (e.g. one cycle's, cycle_frames.hpp): all sent back to back, then
  // replies taken in whatever order they come until each frame has its own or `timeout` has passed
  // since the last send. Returns the answered frames as a mask (bit i: frames[i]); so at most 64
  // frames, and any beyond the 64th are not sent (CycleFrames refuses to make more).
  std::uint64_t exchange(std::span<Frame> frames, Nanos timeout);
  // Lets time pass until `deadline`, discarding whatever arrives (late replies). On a real link
  // this sleeps in the socket wait; under a virtual clock the link moves time.
  void idle_until(Nanos deadline);
  // Next datagram index (wraps at 256).
  std::uint8_t next_index() { return index_++; }
  // The first of `count` consecutive indexes (one cycle's datagrams).
  std::uint8_t next_indexes(std::uint8_t count) {
    const std::uint8_t first = index_;
    index_ = static_cast<std::uint8_t>(index_ + count);
    return first;
  }

  const Clock& clock() const { return clock_; }
  const TransportOptions& options() const { return options_; }
  std::uint64_t frames_sent() const { return frames_sent_; }
  std::uint64_t timeouts() const { return timeouts_; }

  // ---- one datagram per call -----------------------------------------------------------------
  // `position` counts from 0 at the first slave (sent as ADP = -position). Reads fill `data`,
  // read-write calls send `data` and replace it with the reply.
  Wkc aprd(std::uint16_t position, std::uint16_t ado, std::span<std::uint8_t> data);
  Wkc apwr(std::uint16_t position, std::uint16_t ado, std::span<const std::uint8_t> data);
  Wkc aprw(std::uint16_t position, std::uint16_t ado, std::span<std::uint8_t> data);
  Wkc fprd(std::uint16_t station, std::uint16_t ado, std::span<std::uint8_t> data);
  Wkc fpwr(std::uint16_t station, std::uint16_t ado, std::span<const std::uint8_t> data);
  Wkc fprw(std::uint16_t station, std::uint16_t ado, std::span<std::uint8_t> data);
  Wkc brd(std::uint16_t ado, std::span<std::uint8_t> data);
  Wkc bwr(std::uint16_t ado, std::span<const std::uint8_t> data);
  Wkc lrd(std::uint32_t logical, std::span<std::uint8_t> data);
  Wkc lwr(std::uint32_t logical, std::span<const std::uint8_t> data);
  Wkc lrw(std::uint32_t logical, std::span<std::uint8_t> data);
  Wkc armw(std::uint16_t position, std::uint16_t ado, std::span<std::uint8_t> data);
  Wkc frmw(std::uint16_t station, std::uint16_t ado, std::span<std::uint8_t> data);

  // Little-endian register helpers for 1, 2 and 4 byte registers.
  template <class T> Wkc fpwr_value(std::uint16_t station, std::uint16_t ado, T value);
  template <class T> Wkc bwr_value(std::uint16_t ado, T value);
  template <class T> Wkc apwr_value(std::uint16_t position, std::uint16_t ado, T value);
  template <class T> std::optional<T> fprd_value(std::uint16_t station, std::uint16_t ado);  // needs WKC 1

private:
  Wkc single(Command cmd, std::uint32_t address, std::span<std::uint8_t> inout, bool send_data);

  link::Link& link_;
  const Clock& clock_;
  TransportOptions options_;
  Frame frame_;
  std::array<std::uint8_t, link::kMaxFrame> rx_{};
  std::uint8_t index_ = 0;
  std::uint64_t frames_sent_ = 0;
  std::uint64_t timeouts_ = 0;
};

// Auto-increment address for slave `position` (0 = first slave): ADP = -position, ADO = register.
constexpr std::uint32_t position_address(std::uint16_t position, std::uint16_t ado) {
  return static_cast<std::uint32_t>(static_cast<std::uint16_t>(0u - position)) |
         (static_cast<std::uint32_t>(ado) << 16);
}
constexpr std::uint32_t station_address(std::uint16_t station, std::uint16_t ado) {
  return static_cast<std::uint32_t>(station) | (static_cast<std::uint32_t>(ado) << 16);
}

}  // namespace vdrive::master

#include "master/transport_values.hpp"
