#pragma once
// The one source of time. Nothing in vdrive reads the system clock directly: the real-time
// program uses MonotonicClock, tests and scenarios use VirtualClock (deterministic, advanced
// explicitly, faster than real time).
#include <cstdint>

namespace vdrive {

using Nanos = std::int64_t;  // nanoseconds since the clock's epoch

class Clock {
public:
  virtual ~Clock() = default;
  virtual Nanos now() const = 0;
};

// CLOCK_MONOTONIC, epoch = creation of the clock object, or an epoch given as a CLOCK_MONOTONIC
// reading (processes of one run on one host share their times so).
class MonotonicClock final : public Clock {
public:
  MonotonicClock();
  explicit MonotonicClock(Nanos origin) : origin_(origin) {}
  Nanos now() const override;
  Nanos origin() const { return origin_; }

private:
  Nanos origin_;
};

// Time that moves only when told to.
class VirtualClock final : public Clock {
public:
  explicit VirtualClock(Nanos start = 0) : now_(start) {}
  Nanos now() const override { return now_; }
  void advance(Nanos dt) { now_ += dt; }
  void set(Nanos t) { now_ = t; }

private:
  Nanos now_;
};

}  // namespace vdrive
