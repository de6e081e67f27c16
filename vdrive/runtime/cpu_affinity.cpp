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

bool cpu_is_allowed(int cpu) {
  if (cpu < 0 || cpu >= CPU_SETSIZE) return false;
  cpu_set_t set;
  CPU_ZERO(&set);
  return ::sched_getaffinity(0, sizeof set, &set) == 0 && CPU_ISSET(static_cast<unsigned>(cpu), &set);
}

}  // namespace vdrive::runtime
