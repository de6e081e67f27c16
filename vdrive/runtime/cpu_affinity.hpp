#pragma once
// Pinning the serving thread to one CPU (`vdrive run --cpu N`): the frame path then never migrates
// between cores (cold caches, a wake-up on a busy core), and the CPU can be kept free of other work
// (isolcpus, a cpuset). Threads started before the pinning keep their own affinity.

namespace vdrive::runtime {

// Pins the calling thread to CPU `cpu`. Returns 0, or the errno of sched_setaffinity (EINVAL: no
// such CPU, or not in this process's allowed set).
int pin_to_cpu(int cpu);
// Whether this process may run on CPU `cpu` (so that --cpu can be refused before anything starts).
bool cpu_is_allowed(int cpu);

}  // namespace vdrive::runtime
