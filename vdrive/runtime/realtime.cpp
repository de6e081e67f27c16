#include "vdrive/runtime/realtime.hpp"

#include <sched.h>
#include <sys/mman.h>

#include <cerrno>

namespace vdrive::runtime {

RealtimeResult enter_realtime(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  if (::sched_setscheduler(0, SCHED_FIFO, &param) != 0) return {errno, "sched_setscheduler"};
  if (::mlockall(MCL_CURRENT | MCL_FUTURE) != 0) return {errno, "mlockall"};
  return {};
}

}  // namespace vdrive::runtime
