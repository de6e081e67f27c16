#pragma once
// How many requests a control surface passes on to the line: a token bucket of `burst` requests,
// refilled at `per_second`. The control socket, DDS control and the web API's changes each keep
// one; a request over the bound is answered at once ("too many requests", with how long to wait)
// and never reaches the event loop, so a runaway script cannot crowd the loop that serves frames.
// Not on the frame path; take() may be called from any thread.
#include <mutex>
#include <string>

#include "common/clock.hpp"

namespace vdrive::control {

// The bound every surface uses: far above what a person or a test script sends, far below what
// would cost the loop noticeable time (each request is one handoff to it).
inline constexpr double kRequestsPerSecond = 100.0;
inline constexpr double kRequestBurst = 50.0;

class RequestRate {
public:
  RequestRate(double per_second = kRequestsPerSecond, double burst = kRequestBurst);
  // True: go on (one request taken). False: over the bound; `wait` (if given) is how long until
  // one more is allowed. Now, in wall-clock time (requests come in it, whatever the line's clock).
  bool take(Nanos* wait = nullptr) { return take_at(clock_.now(), wait); }
  bool take_at(Nanos now, Nanos* wait = nullptr);
  // "too many requests: at most 100 a second (50 at once); try again in 10 ms"
  std::string refusal(Nanos wait) const;

private:
  MonotonicClock clock_;
  std::mutex mutex_;
  double per_second_, burst_;
  double tokens_;
  Nanos last_ = 0;
  bool started_ = false;
};

}  // namespace vdrive::control
