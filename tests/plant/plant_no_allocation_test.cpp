// Stepping a built plant allocates nothing through operator new (the hot path rule). This binary
// (test_plant) counts every operator new; ODE's own step arena is reserved by the first step.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "plant/plant.hpp"
#include "plant/plant_yaml.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vdrive::plant {
namespace {

TEST(PlantAllocation, SteppingTheTwoLinkArmAllocatesNothing) {
  Plant p(load_plant_file(std::string(VDRIVE_SOURCE_DIR) + "/scenarios/plants/two_link_arm.yaml"));
  AxisCommand c;
  c.torque_nm = 0.2;
  p.command(0, c);
  p.step();  // first step: ODE reserves its step memory
  const long before = g_allocations.load();
  for (int i = 0; i < 1000; ++i) {
    c.torque_nm = (i & 64) ? 0.2 : -0.2;
    p.command(0, c);
    p.command(1, c);
    p.step();
  }
  p.advance_to(p.time() + 10'000'000);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_NE(p.feedback(0).encoder.counts, 0);
}

}  // namespace
}  // namespace vdrive::plant
