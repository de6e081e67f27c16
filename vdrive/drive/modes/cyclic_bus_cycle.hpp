#pragma once
// When the master's cyclic set-points arrive and how far apart. The master writes the targets once
// per bus cycle (60C2h interpolation time period = the cycle: A6B L30497-L30515, DS1000A-EC L2262-
// L2270); the drive's control step is shorter. A new set-point is known either from the engine
// (on_cycle(): outputs were taken over at SYNC0 / the SM2 event, even if the values repeat) or,
// for an engine that does not call on_cycle(), from a change of the value.
#include <cstdint>

#include "common/clock.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class CyclicBusCycle {
public:
  explicit CyclicBusCycle(od::ObjectStore& objects)
      : period_value_(objects, 0x60C2, 1), period_index_(objects, 0x60C2, 2, -3) {}

  // Forget a set-point announced before the mode took over.
  void reset() { pending_ = false; }

  void on_cycle(Nanos now) {
    if (driven_ && now > last_cycle_) note_interval(now - last_cycle_);
    driven_ = true;
    pending_ = true;
    last_cycle_ = now;
  }

  // True when a new set-point is to be taken in the step at `step_time` (AxisSample::time, where
  // the step begins: its output holds until the next step); `at` = when it arrived. Detected by a
  // change of value, it is taken as arrived at the step that sees it: dating it a step earlier
  // would end each one-cycle segment a step before the next set-point is seen, with no demand
  // rate (csp velocity feed-forward) in that step.
  bool take_new(bool value_changed, Nanos step_time, Nanos& at) {
    if (driven_) {
      if (!pending_) return false;
      pending_ = false;
      at = last_cycle_;
      return true;
    }
    at = step_time;
    return value_changed;
  }

  bool driven() const { return driven_; }
  Nanos last_cycle() const { return last_cycle_; }

  // The bus cycle: measured between on_cycle() calls once steady, else 60C2h (value * 10^index s),
  // else 1 ms. A real drive's SYNC0 interrupt is exact; ours is taken when the host's loop gets to
  // it, so one late cycle is followed by a short one. A single interval more than a quarter off
  // the period in use is that jitter and ignored (it would shrink the A6B's per-cycle step limit
  // and raise a false Err27.4); a new period is adopted once it repeats kSteadyIntervals times.
  Nanos period() const {
    if (measured_ >= kMinPeriod && measured_ <= kMaxPeriod) return measured_;
    const std::int64_t value = period_value_.get();
    const std::int64_t index = period_index_.get();
    if (value > 0 && index >= -9 && index <= 0) {
      Nanos ns = value;
      for (std::int64_t e = -9; e < index; ++e) ns *= 10;
      if (ns >= kMinPeriod && ns <= kMaxPeriod) return ns;
    }
    return 1'000'000;
  }

private:
  static constexpr Nanos kMinPeriod = 10'000, kMaxPeriod = 1'000'000'000;
  static constexpr int kSteadyIntervals = 4;

  static bool near(Nanos interval, Nanos period) { return 4 * (interval > period ? interval - period : period - interval) <= period; }

  void note_interval(Nanos interval) {
    if (measured_ != 0 && near(interval, measured_)) {
      measured_ += (interval - measured_) / 8;   // follows a slow drift, smooths the jitter
      run_ = 0;
      return;
    }
    if (run_ > 0 && near(interval, candidate_)) {
      ++run_;
    } else {
      candidate_ = interval;
      run_ = 1;
    }
    if (run_ >= kSteadyIntervals) {
      measured_ = candidate_;
      run_ = 0;
    }
  }

  ObjectRef<std::uint8_t> period_value_;
  ObjectRef<std::int8_t> period_index_;
  bool driven_ = false;
  bool pending_ = false;
  Nanos last_cycle_ = 0;
  Nanos measured_ = 0;    // 0 = not steady yet
  Nanos candidate_ = 0;   // an interval off measured_, and how often in a row it came
  int run_ = 0;
};

}  // namespace vdrive::drive
