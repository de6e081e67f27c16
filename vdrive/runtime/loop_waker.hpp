#pragma once
// LoopWaker: lets another thread cut the event loop's wait short, so work it hands over (a
// control request) is picked up now rather than at the end of the wait (up to kMaxWait). It
// sends SIGUSR1 to the loop's thread, whose no-op handler (installed without SA_RESTART) makes
// the link's ppoll/recvfrom return EINTR: the links then return "nothing arrived" and serve()
// goes round (the same path a stop signal takes). A signal that lands just before the loop
// enters its wait is absorbed and the work waits for the next wake-up as before: a wake-up is
// a hint, never needed for correctness.
#include <pthread.h>

namespace vdrive::runtime {

class LoopWaker {
public:
  // On the loop's thread, before serve().
  LoopWaker();
  // Any thread.
  void wake() const;

private:
  pthread_t loop_thread_;
};

}  // namespace vdrive::runtime
