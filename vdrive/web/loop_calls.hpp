#pragma once
// LoopCalls: work another thread hands to the event loop's thread, which owns the network. The
// web server's threads read registers and objects and change the line through it, as the control
// socket does through FaultService. run() queues the work and waits for it; poll() runs what is
// queued between frames. A caller that gives up (timeout) is told so, and its work then never
// runs, so work may refer to the caller's stack. poll() with nothing queued is one atomic load.
#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>

#include "common/clock.hpp"
#include "vdrive/runtime/loop_service.hpp"
#include "vdrive/runtime/spsc_queue.hpp"

namespace vdrive::web {

class LoopCalls final : public runtime::LoopService {
public:
  using Work = std::function<void(Nanos now)>;

  // `wake` (optional) cuts the loop's wait short after work is queued (runtime::LoopWaker).
  explicit LoopCalls(std::function<void()> wake = {});
  ~LoopCalls() override;

  // Loop thread.
  void poll(Nanos now) override;
  Nanos next_deadline() const override { return std::numeric_limits<Nanos>::max(); }

  // Any thread: runs `work` on the loop thread and returns true once it has run; false if the
  // loop did not start it within `timeout` (it never will).
  bool run(Work work, Nanos timeout);
  // Any thread, when the loop stops polling for good: waiting and later calls return false at once.
  void close() { closed_.store(true); }

private:
  struct Job {
    enum State : int { queued, running, done, abandoned };
    Work work;
    std::atomic<int> state{queued};
  };
  std::function<void()> wake_;
  std::atomic<bool> closed_{false};
  std::mutex producers_;  // callers only: the queue has one producer at a time
  runtime::SpscQueue<std::shared_ptr<Job>, 16> queue_;
};

}  // namespace vdrive::web
