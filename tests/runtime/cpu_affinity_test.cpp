// runtime::pin_to_cpu: the calling thread (only it) ends up allowed on exactly that CPU; a CPU
// that does not exist is refused with EINVAL and changes nothing.
#include <gtest/gtest.h>

#include <sched.h>

#include <cerrno>
#include <thread>

#include "vdrive/runtime/cpu_affinity.hpp"

namespace vdrive::runtime {
namespace {

cpu_set_t affinity() {
  cpu_set_t set;
  CPU_ZERO(&set);
  EXPECT_EQ(::sched_getaffinity(0, sizeof set, &set), 0);
  return set;
}

// The last CPU this process may run on (pinning to it is always allowed).
int some_allowed_cpu() {
  const cpu_set_t set = affinity();
  for (int cpu = CPU_SETSIZE - 1; cpu >= 0; --cpu)
    if (CPU_ISSET(cpu, &set)) return cpu;
  return -1;
}

TEST(CpuAffinity, PinsTheCallingThreadOnly) {
  const int cpu = some_allowed_cpu();
  ASSERT_GE(cpu, 0);
  const cpu_set_t initial = affinity();
  const int before = CPU_COUNT(&initial);
  std::thread([cpu] {
    EXPECT_EQ(pin_to_cpu(cpu), 0);
    const cpu_set_t set = affinity();
    EXPECT_EQ(CPU_COUNT(&set), 1);
    EXPECT_TRUE(CPU_ISSET(cpu, &set));
  }).join();
  const cpu_set_t after = affinity();
  EXPECT_EQ(CPU_COUNT(&after), before);  // the test's own thread is untouched
}

TEST(CpuAffinity, AllowedCpusAreThoseOfTheAffinityMask) {
  const cpu_set_t set = affinity();
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) EXPECT_EQ(cpu_is_allowed(cpu), CPU_ISSET(cpu, &set) != 0) << "CPU " << cpu;
  EXPECT_FALSE(cpu_is_allowed(-1));
  EXPECT_FALSE(cpu_is_allowed(CPU_SETSIZE));
}

TEST(CpuAffinity, MissingCpuIsRefused) {
  std::thread([] {
    const cpu_set_t before = affinity();
    EXPECT_EQ(pin_to_cpu(CPU_SETSIZE - 1), EINVAL);  // no machine here has 1024 CPUs
    EXPECT_EQ(pin_to_cpu(-1), EINVAL);
    EXPECT_EQ(pin_to_cpu(CPU_SETSIZE), EINVAL);
    const cpu_set_t after = affinity();
    EXPECT_TRUE(CPU_EQUAL(&before, &after));
  }).join();
}

}  // namespace
}  // namespace vdrive::runtime
