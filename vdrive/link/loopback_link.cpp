// In-process link pair over two SPSC frame rings; see loopback_link.hpp.
#include "vdrive/link/loopback_link.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>
#include <thread>

namespace vdrive::link {
namespace {

constexpr std::uint16_t kEtherTypeVlan = 0x8100;
constexpr std::size_t kEthernetHeader = 14;

std::uint16_t be16(const std::uint8_t* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }

bool is_ethercat(std::span<const std::uint8_t> frame) {
  if (frame.size() < kEthernetHeader) return false;
  std::uint16_t type = be16(&frame[12]);
  if (type == kEtherTypeVlan) {
    if (frame.size() < kEthernetHeader + 4) return false;
    type = be16(&frame[16]);
  }
  return type == kEtherTypeEtherCat;
}

// Waiting strategy: spin this long, then yield this long, then sleep in short steps.
constexpr Nanos kSpinFor = 5'000;
constexpr Nanos kYieldFor = 100'000;
constexpr Nanos kSleepStep = 50'000;

}  // namespace

// ---- FrameRing --------------------------------------------------------------------------------

FrameRing::FrameRing(std::size_t capacity)
    : slots_(std::make_unique<Slot[]>(std::bit_ceil(std::max<std::size_t>(capacity, 1)))),
      mask_(std::bit_ceil(std::max<std::size_t>(capacity, 1)) - 1) {}

bool FrameRing::push(std::span<const std::uint8_t> frame) {
  if (frame.size() > kMaxFrame) return false;
  const std::size_t head = head_.load(std::memory_order_relaxed);
  if (head - tail_.load(std::memory_order_acquire) > mask_) return false;  // full
  Slot& slot = slots_[head & mask_];
  slot.length = static_cast<std::uint16_t>(frame.size());
  std::memcpy(slot.data, frame.data(), frame.size());
  head_.store(head + 1, std::memory_order_release);
  return true;
}

std::size_t FrameRing::pop(std::span<std::uint8_t> out, bool& too_long) {
  too_long = false;
  const std::size_t tail = tail_.load(std::memory_order_relaxed);
  if (tail == head_.load(std::memory_order_acquire)) return 0;
  const Slot& slot = slots_[tail & mask_];
  std::size_t n = slot.length;
  if (n > out.size()) {
    too_long = true;
    n = 0;
  } else {
    std::memcpy(out.data(), slot.data, n);
  }
  tail_.store(tail + 1, std::memory_order_release);
  return n;
}

bool FrameRing::empty() const {
  return tail_.load(std::memory_order_acquire) == head_.load(std::memory_order_acquire);
}

// ---- LoopbackLink -----------------------------------------------------------------------------

struct LoopbackLink::Pair {
  explicit Pair(std::size_t slots) : a_to_b(slots), b_to_a(slots) {}
  FrameRing a_to_b;
  FrameRing b_to_a;
  MonotonicClock clock;  // for receive timeouts only
};

std::pair<std::unique_ptr<LoopbackLink>, std::unique_ptr<LoopbackLink>> make_loopback_pair(std::size_t slots) {
  auto pair = std::make_shared<LoopbackLink::Pair>(slots);
  std::unique_ptr<LoopbackLink> a(new LoopbackLink(pair, pair->b_to_a, pair->a_to_b));
  std::unique_ptr<LoopbackLink> b(new LoopbackLink(pair, pair->a_to_b, pair->b_to_a));
  return {std::move(a), std::move(b)};
}

bool LoopbackLink::send(std::span<const std::uint8_t> frame) { return tx_.push(frame); }

std::size_t LoopbackLink::try_receive(std::span<std::uint8_t> buf) {
  while (!rx_.empty()) {
    bool too_long = false;
    const std::size_t n = rx_.pop(buf, too_long);
    if (too_long || !is_ethercat(buf.first(n))) {
      ++discarded_;
      continue;
    }
    return n;
  }
  return 0;
}

std::size_t LoopbackLink::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  if (const std::size_t n = try_receive(buf)) return n;
  if (timeout == 0) return 0;
  const Clock& clock = pair_->clock;
  const Nanos start = clock.now();
  for (;;) {
    if (const std::size_t n = try_receive(buf)) return n;
    const Nanos waited = clock.now() - start;
    if (timeout > 0 && waited >= timeout) return 0;
    if (waited < kSpinFor) continue;
    if (waited < kYieldFor) {
      std::this_thread::yield();
      continue;
    }
    Nanos step = kSleepStep;
    if (timeout > 0) step = std::min(step, timeout - waited);
    std::this_thread::sleep_for(std::chrono::nanoseconds(step));
  }
}

}  // namespace vdrive::link
