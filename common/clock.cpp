#include "common/clock.hpp"

#include <ctime>

namespace vdrive {
namespace {
Nanos monotonic_raw() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<Nanos>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
}  // namespace

MonotonicClock::MonotonicClock() : origin_(monotonic_raw()) {}
Nanos MonotonicClock::now() const { return monotonic_raw() - origin_; }

}  // namespace vdrive
