#pragma once
// LoopbackLink: an in-process pair of Link endpoints, e.g. a master on one thread and the network
// event loop on another, or both on one thread under a VirtualClock (then receive with timeout 0).
//
// - Each direction is a lock-free single-producer/single-consumer ring of fixed-size frame slots
//   (kMaxFrame bytes each), allocated once by make_loopback_pair(); send/receive allocate nothing.
//   One thread per endpoint: endpoint A's send() and B's receive() may run concurrently.
// - send() refuses (returns false) a frame longer than kMaxFrame or when the ring is full, as a
//   NIC whose queue is full drops; it never blocks.
// - receive() delivers EtherCAT frames only (EtherType 0x88A4, also behind one 802.1Q tag);
//   other frames are discarded, as are frames longer than the caller's buffer (counted).
// - A timeout > 0 waits on the monotonic clock: brief spinning, then yielding, then short
//   sleeps, so a waiting thread costs little CPU and a frame is picked up within ~50 us.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>

#include "vdrive/link/link.hpp"

namespace vdrive::link {

// Fixed-capacity SPSC ring of Ethernet frames. Capacity is rounded up to a power of two.
class FrameRing {
public:
  explicit FrameRing(std::size_t capacity);
  FrameRing(const FrameRing&) = delete;
  FrameRing& operator=(const FrameRing&) = delete;

  // Producer side. False if full or the frame is larger than a slot.
  bool push(std::span<const std::uint8_t> frame);
  // Consumer side. Copies the oldest frame into `out` and returns its length; 0 if empty.
  // A frame longer than `out` is dropped and reported as `too_long` (returns 0).
  std::size_t pop(std::span<std::uint8_t> out, bool& too_long);
  bool empty() const;
  std::size_t capacity() const { return mask_ + 1; }

private:
  struct Slot {
    std::uint16_t length;
    std::uint8_t data[kMaxFrame];
  };
  std::unique_ptr<Slot[]> slots_;
  std::size_t mask_;
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot to write (producer)
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot to read (consumer)
};

class LoopbackLink final : public Link {
public:
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override;
  bool send(std::span<const std::uint8_t> frame) override;
  PeekCost peek_cost() const override { return PeekCost::Free; }
  bool frame_waiting() override { return !rx_.empty(); }

  // Frames taken from the ring but not returned: not EtherCAT, or too long for the buffer.
  std::uint64_t discarded() const { return discarded_; }

private:
  struct Pair;
  friend std::pair<std::unique_ptr<LoopbackLink>, std::unique_ptr<LoopbackLink>> make_loopback_pair(std::size_t);
  LoopbackLink(std::shared_ptr<Pair> pair, FrameRing& rx, FrameRing& tx) : pair_(std::move(pair)), rx_(rx), tx_(tx) {}
  std::size_t try_receive(std::span<std::uint8_t> buf);

  std::shared_ptr<Pair> pair_;  // keeps both rings alive while either endpoint exists
  FrameRing& rx_;
  FrameRing& tx_;
  std::uint64_t discarded_ = 0;
};

// Two connected endpoints: what one sends, the other receives. `slots` frames per direction.
std::pair<std::unique_ptr<LoopbackLink>, std::unique_ptr<LoopbackLink>> make_loopback_pair(std::size_t slots = 64);

}  // namespace vdrive::link
