#pragma once
// A fixed ring of whole mailbox messages (header + payload) waiting for SM1. Storage is
// allocated once at construction; push/pop only copy bytes.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vdrive::firmware::mailbox {

class ReplyQueue {
public:
  ReplyQueue(std::size_t slots, std::size_t slot_bytes)
      : bytes_(slots * slot_bytes), lengths_(slots), slot_bytes_(slot_bytes) {}

  std::size_t size() const { return count_; }
  std::size_t capacity() const { return lengths_.size(); }
  bool full() const { return count_ == lengths_.size(); }
  bool empty() const { return count_ == 0; }

  // The slot a new message at the back would use (fill it, then commit_back).
  std::span<std::uint8_t> back_slot() { return slot((head_ + count_) % capacity()); }
  void commit_back(std::size_t length) {
    lengths_[(head_ + count_) % capacity()] = length;
    ++count_;
  }
  // Puts a message back in front (a reply the master asked to repeat displaced it).
  void push_front(std::span<const std::uint8_t> message) {
    if (full()) return;
    head_ = (head_ + capacity() - 1) % capacity();
    const std::size_t n = std::min(message.size(), slot_bytes_);
    std::copy_n(message.begin(), n, slot(head_).begin());
    lengths_[head_] = n;
    ++count_;
  }
  std::span<const std::uint8_t> front() const {
    return std::span<const std::uint8_t>(bytes_.data() + head_ * slot_bytes_, lengths_[head_]);
  }
  void pop_front() {
    head_ = (head_ + 1) % capacity();
    --count_;
  }
  void clear() { head_ = count_ = 0; }

private:
  std::span<std::uint8_t> slot(std::size_t i) {
    return std::span<std::uint8_t>(bytes_.data() + i * slot_bytes_, slot_bytes_);
  }
  std::vector<std::uint8_t> bytes_;
  std::vector<std::size_t> lengths_;
  std::size_t slot_bytes_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

}  // namespace vdrive::firmware::mailbox
