#pragma once
// SpscQueue: a bounded lock-free queue between exactly one producer thread and one consumer
// thread (Lamport's ring with acquire/release indices). try_push/try_pop never block, never
// allocate and never take a lock; the slots are default-constructed up front and values are
// moved in and out. The control channel uses it to hand requests to the event loop and replies
// back (docs/cli.md "Runtime control").
#include <array>
#include <atomic>
#include <cstddef>
#include <optional>
#include <utility>

namespace vdrive::runtime {

template <typename T, std::size_t Capacity>
class SpscQueue {
  static_assert(Capacity > 0);

public:
  // Producer only. False (and `value` untouched) when full.
  bool try_push(T&& value) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail - head_.load(std::memory_order_acquire) == Capacity) return false;
    slots_[tail % Capacity] = std::move(value);
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Consumer only. nullopt when empty; an empty check is one acquire load.
  std::optional<T> try_pop() {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (tail_.load(std::memory_order_acquire) == head) return std::nullopt;
    std::optional<T> value(std::move(slots_[head % Capacity]));
    head_.store(head + 1, std::memory_order_release);
    return value;
  }

  // Consumer only: true if try_pop() would return nothing.
  bool empty() const {
    return tail_.load(std::memory_order_acquire) == head_.load(std::memory_order_relaxed);
  }

private:
  std::array<T, Capacity> slots_{};
  // Separate cache lines: the producer writes tail_, the consumer head_.
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace vdrive::runtime
