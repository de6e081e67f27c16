#pragma once
// What a recovering master keeps of one CiA 402 drive's outages: an outage starts when a drive
// that was in Operation enabled leaves it (a fault, or a disable that an AL error forced) and
// ends when it is enabled again; its 603Fh error code is the first non-zero one seen meanwhile.
// An outage longer than the bound is overdue: the drive did not come back, which the caller
// reports as a failure (the drive may still come back later; the outage stays overdue).
//
// update() runs in every cycle and allocates nothing: the codes are counted in a fixed table, and
// codes beyond its size in `other_codes`.
#include <array>
#include <cstdint>
#include <span>

#include "common/clock.hpp"

namespace vdrive::master {

struct AlarmCount {
  std::uint16_t code = 0;   // 603Fh; 0: the drive was disabled without an error code
  std::uint64_t count = 0;
};

class DriveRecovery {
public:
  enum class Event { none, lost, recovered, overdue };

  DriveRecovery() = default;
  explicit DriveRecovery(Nanos bound) : bound_(bound) {}

  // One cycle: `enabled` is Operation enabled in the mode the program runs, `error_code` 603Fh.
  // Returns what changed in this cycle (at most one event).
  Event update(Nanos now, bool enabled, std::uint16_t error_code);

  bool out() const { return out_since_ >= 0; }
  std::uint64_t outages() const { return outages_; }
  std::uint64_t recoveries() const { return recoveries_; }
  std::uint64_t overdue() const { return overdue_; }
  Nanos longest() const { return longest_; }
  Nanos last_duration() const { return last_duration_; }
  std::uint16_t code() const { return code_; }  // of the current or last outage
  std::span<const AlarmCount> codes() const { return {codes_.data(), used_}; }
  std::uint64_t other_codes() const { return other_codes_; }

private:
  void count(std::uint16_t code);

  Nanos bound_ = 10'000'000'000;
  bool was_enabled_ = false;
  Nanos out_since_ = -1;
  bool out_overdue_ = false;    // the current outage passed the bound (and its code is counted)
  std::uint16_t code_ = 0;
  std::uint64_t outages_ = 0, recoveries_ = 0, overdue_ = 0, other_codes_ = 0;
  Nanos longest_ = 0, last_duration_ = 0;
  std::array<AlarmCount, 8> codes_{};
  std::size_t used_ = 0;
};

}  // namespace vdrive::master
