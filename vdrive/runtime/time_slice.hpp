#pragma once
// A shorter time slice for the serving thread under the normal scheduler (SCHED_OTHER), as
// Linux 6.12 and later grant it (EEVDF custom slices: sched_attr.sched_runtime, 0.1-100 ms). The
// slice sets how soon a waking task may preempt: with the default (about 3 ms) a frame or a SYNC
// deadline that wakes the loop while a kernel thread or another process runs on its CPU waits
// for that task's slice to end; with a short one it preempts at once. No privilege is needed.
#include "common/clock.hpp"

namespace vdrive::runtime {

inline constexpr Nanos kMinTimeSlice = 100'000;      // what the kernel grants at the least
inline constexpr Nanos kMaxTimeSlice = 100'000'000;  // and at the most

// Asks for `slice` (kMinTimeSlice..kMaxTimeSlice) for the calling thread, keeping its policy's
// nice value. Returns 0, or an errno: EINVAL for a slice out of range or a thread not under
// SCHED_OTHER, ENOTSUP when the kernel took the call but kept no such slice (before 6.12).
int set_time_slice(Nanos slice);

// The calling thread's slice as the kernel reports it (0: none set, or not reported).
Nanos time_slice();

}  // namespace vdrive::runtime
