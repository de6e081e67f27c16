#pragma once
// LoopService: work that runs on the event loop's thread next to the line, e.g. the runtime
// fault control (vdrive/control/fault_service.hpp). serve() calls poll() once per iteration,
// before it waits, and never waits past next_deadline(). poll() must be cheap when there is
// nothing to do (a load or two): it sits on the frame path.
#include "common/clock.hpp"

namespace vdrive::runtime {

class LoopService {
public:
  virtual ~LoopService() = default;
  // Handles what is pending and due by `now`.
  virtual void poll(Nanos now) = 0;
  // When poll() next has work of its own (INT64_MAX: none). Work handed over from another
  // thread is noticed at the next iteration, at most kMaxWait later.
  virtual Nanos next_deadline() const = 0;
};

}  // namespace vdrive::runtime
