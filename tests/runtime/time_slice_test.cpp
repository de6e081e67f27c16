// runtime::set_time_slice: the calling thread (only it) gets the slice the kernel reports back;
// out-of-range slices and threads not under SCHED_OTHER are refused with EINVAL.
#include "vdrive/runtime/time_slice.hpp"

#include <gtest/gtest.h>

#include <sched.h>

#include <cerrno>
#include <thread>

namespace vdrive::runtime {
namespace {

TEST(TimeSlice, TheCallingThreadGetsItsSliceAndNoOtherThread) {
  const Nanos before = time_slice();
  int result = -1;
  Nanos got = 0;
  std::thread([&] {
    result = set_time_slice(200'000);
    got = time_slice();
  }).join();
  if (result == ENOTSUP) GTEST_SKIP() << "this kernel keeps no slice of a thread's own (Linux 6.12+ does)";
  ASSERT_EQ(result, 0);
  EXPECT_EQ(got, 200'000);
  EXPECT_EQ(time_slice(), before) << "another thread's slice changed too";
}

TEST(TimeSlice, OutOfRangeIsRefusedAndChangesNothing) {
  std::thread([] {
    const Nanos before = time_slice();
    EXPECT_EQ(set_time_slice(kMinTimeSlice - 1), EINVAL);
    EXPECT_EQ(set_time_slice(kMaxTimeSlice + 1), EINVAL);
    EXPECT_EQ(time_slice(), before);
  }).join();
}

TEST(TimeSlice, AThreadUnderSchedFifoIsRefused) {
  std::thread([] {
    sched_param param{};
    param.sched_priority = 1;
    if (::sched_setscheduler(0, SCHED_FIFO, &param) != 0) GTEST_SKIP() << "SCHED_FIFO needs root";
    EXPECT_EQ(set_time_slice(200'000), EINVAL);
  }).join();
}

}  // namespace
}  // namespace vdrive::runtime
