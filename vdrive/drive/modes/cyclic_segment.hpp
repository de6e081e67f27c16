#pragma once
// The set-point between two bus set-points: a straight line from where the demand was when a new
// set-point arrived to that set-point, one bus cycle later (one cycle of delay, no step in the
// demand). If the next set-point is late or lost, the line is extended with the last increment
// per cycle for a bounded time, as the A6B compensates a missed 607Ah (L16888-L16917), and then
// holds. Pure value type; no allocation.
#include <algorithm>

#include "common/clock.hpp"

namespace vdrive::drive {

class CyclicSegment {
public:
  void hold(double value) {
    from_ = to_ = value;
    duration_ = 1;
    extrapolate_ = 0;
  }

  // From `from` at `start` to `to` at start + duration; then on at the same rate for at most
  // `extrapolate` more.
  void start(double from, double to, Nanos start, Nanos duration, Nanos extrapolate) {
    from_ = from;
    to_ = to;
    start_ = start;
    duration_ = std::max<Nanos>(duration, 1);
    extrapolate_ = std::max<Nanos>(extrapolate, 0);
  }

  double value_at(Nanos t) const {
    const Nanos into = std::clamp<Nanos>(t - start_, 0, duration_ + extrapolate_);
    return from_ + (to_ - from_) * static_cast<double>(into) / static_cast<double>(duration_);
  }

  // Rate of change at t (units per second): the line's slope while it runs, 0 once it holds.
  double rate_at(Nanos t) const {
    const Nanos into = t - start_;
    if (into < 0 || into >= duration_ + extrapolate_) return 0.0;
    return (to_ - from_) / (static_cast<double>(duration_) * 1e-9);
  }

  double goal() const { return to_; }

private:
  double from_ = 0.0, to_ = 0.0;
  Nanos start_ = 0, duration_ = 1, extrapolate_ = 0;
};

}  // namespace vdrive::drive
