#include "vdrive/runtime/cpu_affinity.hpp"

#include <sched.h>

#include <cerrno>

namespace vdrive::runtime {

int pin_to_cpu(int cpu) {
  if (cpu < 0 || cpu >= CPU_SETSIZE) return EINVAL;
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<unsigned>(cpu), &set);
  return ::sched_setaffinity(0, sizeof set, &set) == 0 ? 0 : errno;
}

}  // namespace vdrive::runtime
