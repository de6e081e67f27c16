#pragma once
// The objects the RxPDO mapping in effect carries into the drive every bus cycle, as the firmware
// tells it when a mapping becomes effective (PreOp->SafeOp). Modes ask it which set-points arrive
// cyclically (ip: 60C1h-01h) instead of reading the mapping objects themselves. Fixed capacity:
// copying and asking allocate nothing.
#include <array>
#include <cstddef>
#include <cstdint>

namespace vdrive::drive {

class MappedOutputs {
public:
  // At least as many as a PDO image can map (the firmware checks its own limit against this).
  static constexpr std::size_t kCapacity = 256;

  void clear() { count_ = 0; }
  // Entries beyond kCapacity are dropped (the firmware never maps that many).
  void add(std::uint16_t index, std::uint8_t subindex) {
    if (count_ < kCapacity) entries_[count_++] = key(index, subindex);
  }
  bool contains(std::uint16_t index, std::uint8_t subindex) const {
    const std::uint32_t k = key(index, subindex);
    for (std::size_t i = 0; i < count_; ++i)
      if (entries_[i] == k) return true;
    return false;
  }
  std::size_t size() const { return count_; }

private:
  static constexpr std::uint32_t key(std::uint16_t index, std::uint8_t subindex) {
    return (static_cast<std::uint32_t>(index) << 8) | subindex;
  }
  std::array<std::uint32_t, kCapacity> entries_{};
  std::size_t count_ = 0;
};

}  // namespace vdrive::drive
