// A bad cable between the master and slave 1. See wire_impairment.hpp.
#include "vdrive/fault/wire_impairment.hpp"

#include <algorithm>
#include <limits>

#include "vdrive/link/link.hpp"

namespace vdrive::fault {

namespace {
double probability(double p) { return std::clamp(p, 0.0, 1.0); }
}  // namespace

WireImpairment::WireImpairment(std::uint64_t seed, std::size_t capacity)
    : state_(seed), capacity_(std::max<std::size_t>(capacity, 1)) {
  for (Queue& q : queues_) {
    q.bytes.resize(capacity_ * link::kMaxFrame);
    q.slots.resize(capacity_);
    q.held.bytes.resize(link::kMaxFrame);
  }
}

void WireImpairment::set(Direction d, const WireSettings& s) {
  WireSettings& w = dir(d).settings;
  w.drop = probability(s.drop);
  w.corrupt = probability(s.corrupt);
  w.duplicate = probability(s.duplicate);
  w.reorder = probability(s.reorder);
  w.delay = std::max<Nanos>(s.delay, 0);
}

void WireImpairment::clear() {
  for (Queue& q : queues_) {
    q.settings = WireSettings{};
    release_held(q);
  }
}

// splitmix64 (Steele, Lea, Flood 2014): tiny, fast, and every seed gives a good stream.
double WireImpairment::uniform() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;  // 53 random bits in [0, 1)
}

bool WireImpairment::enqueue(Queue& q, std::span<const std::uint8_t> frame, Nanos release,
                             bool fcs_error) {
  if (q.count == capacity_) return false;
  const std::size_t at = (q.head + q.count) % capacity_;
  std::copy(frame.begin(), frame.end(), q.bytes.begin() + static_cast<std::ptrdiff_t>(at * link::kMaxFrame));
  // No overtaking: a frame never comes out before one offered earlier.
  q.last_release = std::max(q.last_release, release);
  q.slots[at] = Slot{frame.size(), q.last_release, fcs_error};
  ++q.count;
  return true;
}

void WireImpairment::enqueue_copies(Queue& q, std::span<const std::uint8_t> frame, Nanos release,
                                    bool fcs_error, bool duplicate) {
  if (!enqueue(q, frame, release, fcs_error)) {
    ++q.counters.dropped;
    return;
  }
  if (duplicate) enqueue(q, frame, release, fcs_error);  // no room for the copy: just one
}

void WireImpairment::release_held(Queue& q) {
  if (!q.held.present) return;
  q.held.present = false;
  enqueue_copies(q, std::span<const std::uint8_t>(q.held.bytes.data(), q.held.slot.length),
                 q.held.slot.release, q.held.slot.fcs_error, q.held.duplicate);
}

void WireImpairment::push(Direction d, std::span<const std::uint8_t> frame, Nanos now) {
  Queue& q = dir(d);
  const WireSettings& s = q.settings;
  // Always four draws, so one setting never shifts the others' random stream.
  const bool drop = uniform() < s.drop;
  const bool corrupt = uniform() < s.corrupt;
  const bool duplicate = uniform() < s.duplicate;
  const bool reorder = uniform() < s.reorder;
  const Nanos release = now + s.delay;
  const bool was_holding = q.held.present;

  if (drop || frame.size() > link::kMaxFrame) {
    ++q.counters.dropped;
  } else {
    if (corrupt) ++q.counters.corrupted;
    if (duplicate) ++q.counters.duplicated;
    if (reorder && !was_holding) {
      ++q.counters.reordered;
      std::copy(frame.begin(), frame.end(), q.held.bytes.begin());
      q.held.slot = Slot{frame.size(), release, corrupt};
      q.held.duplicate = duplicate;
      q.held.present = true;
      return;
    }
    enqueue_copies(q, frame, release, corrupt, duplicate);
  }
  // The frame held back comes out right behind this one (or in its place if it was lost).
  if (was_holding) release_held(q);
}

std::size_t WireImpairment::pop(Direction d, std::span<std::uint8_t> out, Nanos now,
                                bool& fcs_error) {
  Queue& q = dir(d);
  fcs_error = false;
  if (q.count == 0 || q.slots[q.head].release > now) return 0;
  const Slot& slot = q.slots[q.head];
  const std::size_t n = std::min(slot.length, out.size());
  const auto from = q.bytes.begin() + static_cast<std::ptrdiff_t>(q.head * link::kMaxFrame);
  std::copy(from, from + static_cast<std::ptrdiff_t>(n), out.begin());
  fcs_error = slot.fcs_error;
  if (!fcs_error) ++q.counters.passed;
  q.head = (q.head + 1) % capacity_;
  --q.count;
  return n;
}

std::size_t WireImpairment::pop(Direction d, std::span<std::uint8_t> out, Nanos now) {
  bool fcs_error = false;
  for (;;) {
    const std::size_t n = pop(d, out, now, fcs_error);
    if (n == 0 || !fcs_error) return n;
  }
}

Nanos WireImpairment::next_release(Direction d) const {
  const Queue& q = dir(d);
  return q.count == 0 ? std::numeric_limits<Nanos>::max() : q.slots[q.head].release;
}

}  // namespace vdrive::fault
