#include "vdrive/runtime/time_slice.hpp"

#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>

namespace vdrive::runtime {
namespace {

// The kernel's struct sched_attr (linux/sched/types.h, which clashes with <sched.h>), as of
// SCHED_ATTR_SIZE_VER1.
struct sched_attr {
  std::uint32_t size;
  std::uint32_t sched_policy;
  std::uint64_t sched_flags;
  std::int32_t sched_nice;
  std::uint32_t sched_priority;
  std::uint64_t sched_runtime;  // for SCHED_OTHER since 6.12: the slice
  std::uint64_t sched_deadline;
  std::uint64_t sched_period;
  std::uint32_t sched_util_min;
  std::uint32_t sched_util_max;
};

// glibc 2.36 has no wrappers for these two.
int get_attr(sched_attr& attr) {
  attr = {};
  return ::syscall(SYS_sched_getattr, 0, &attr, sizeof attr, 0) == 0 ? 0 : errno;
}

}  // namespace

int set_time_slice(Nanos slice) {
  if (slice < kMinTimeSlice || slice > kMaxTimeSlice) return EINVAL;
  sched_attr attr{};
  if (const int err = get_attr(attr); err != 0) return err;
  if (attr.sched_policy != SCHED_OTHER) return EINVAL;
  attr.size = sizeof attr;
  attr.sched_flags = 0;
  attr.sched_runtime = static_cast<std::uint64_t>(slice);
  if (::syscall(SYS_sched_setattr, 0, &attr, 0) != 0) return errno;
  return time_slice() == slice ? 0 : ENOTSUP;
}

Nanos time_slice() {
  sched_attr attr{};
  if (get_attr(attr) != 0) return 0;
  return static_cast<Nanos>(attr.sched_runtime);
}

}  // namespace vdrive::runtime
