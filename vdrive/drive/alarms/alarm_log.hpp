#pragma once
// The alarm history as a drive keeps it in its EEPROM: the last `capacity` alarms, oldest first,
// and how many were ever recorded. Fixed storage; record() allocates nothing. It survives
// power_on() of the drive (the object dictionary does not: the history objects are re-published
// from here, as the A6B reads 10F3h back from EEPROM at power-on, L8929-L8931).
#include <array>
#include <cstddef>
#include <cstdint>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

class AlarmLog {
public:
  static constexpr std::size_t kMaxEntries = 14;  // the longest history of any product (A6B 10F3h, L9036-L9038)

  explicit AlarmLog(std::size_t capacity) : capacity_(capacity < kMaxEntries ? capacity : kMaxEntries) {}

  // Appends; when full the oldest entry is dropped (A6B L8948-L8982: the newest stays last).
  void record(const profile::AlarmSpec& alarm) {
    if (capacity_ == 0) return;
    if (size_ == capacity_) {
      for (std::size_t i = 1; i < size_; ++i) entries_[i - 1] = entries_[i];
      --size_;
    }
    entries_[size_++] = &alarm;
    ++total_;
  }
  void clear() { size_ = 0; }

  std::size_t capacity() const { return capacity_; }
  std::size_t size() const { return size_; }
  // i = 0 is the oldest kept entry.
  const profile::AlarmSpec& at(std::size_t i) const { return *entries_[i]; }
  // n = 0 is the newest entry; nullptr past the oldest.
  const profile::AlarmSpec* newest(std::size_t n = 0) const { return n < size_ ? entries_[size_ - 1 - n] : nullptr; }
  std::uint32_t total() const { return total_; }   // every alarm ever recorded (not reset by clear())

private:
  std::size_t capacity_;
  std::array<const profile::AlarmSpec*, kMaxEntries> entries_{};
  std::size_t size_ = 0;
  std::uint32_t total_ = 0;
};

}  // namespace vdrive::drive
