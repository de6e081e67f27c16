#pragma once
// Frame turnaround in the event loop (frame received to reply sent), measured by TimedLink
// around the link the loop serves and read by the Sampler, both on the loop thread: plain
// fields, no atomics. take() returns the period's statistics and starts a new period.
#include <algorithm>
#include <cstdint>
#include <limits>

#include "common/clock.hpp"

namespace vdrive::telemetry {

struct TurnaroundPeriod {
  Nanos last = 0, min = 0, mean = 0, max = 0;  // all 0 when no reply went out
  std::uint64_t count = 0;
};

class TurnaroundStats {
public:
  void add(Nanos t) {
    last_ = t;
    min_ = std::min(min_, t);
    max_ = std::max(max_, t);
    sum_ += t;
    ++count_;
  }
  TurnaroundPeriod take() {
    TurnaroundPeriod p;
    if (count_ != 0) p = {last_, min_, sum_ / static_cast<Nanos>(count_), max_, count_};
    min_ = std::numeric_limits<Nanos>::max();
    max_ = 0;
    sum_ = 0;
    count_ = 0;
    return p;
  }

private:
  Nanos last_ = 0, min_ = std::numeric_limits<Nanos>::max(), max_ = 0, sum_ = 0;
  std::uint64_t count_ = 0;
};

}  // namespace vdrive::telemetry
