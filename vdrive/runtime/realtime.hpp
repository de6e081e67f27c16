#pragma once
// Real-time scheduling for the serving thread, for masters running short cycles (125 us - 1 ms)
// against vdrive: SCHED_FIFO at a given priority, and all memory locked so no page fault lands
// in the frame path. Needs root or CAP_SYS_NICE + CAP_IPC_LOCK.
#include <string>

namespace vdrive::runtime {

struct RealtimeResult {
  int error = 0;         // 0, or the errno of the step that failed (EPERM: not permitted)
  std::string failed;    // which step: "sched_setscheduler" or "mlockall"
};

// Makes the calling thread SCHED_FIFO at `priority` (1..99) and locks current and future memory.
RealtimeResult enter_realtime(int priority);

}  // namespace vdrive::runtime
