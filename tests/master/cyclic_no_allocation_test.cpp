// The cyclic task allocates nothing per cycle (frames, image and callbacks are set up before), on
// the real three-drive line and on a 60-drive line whose image needs two frames, in virtual time.
// This binary counts global operator new for that.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "master/cyclic_task.hpp"
#include "master/master.hpp"
#include "master/process_data.hpp"
#include "tests/master/virtual_line.hpp"

namespace {
std::atomic<std::uint64_t> g_allocations{0};
}

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vdrive::master {
namespace {

TEST(CyclicNoAllocation, CyclesAllocateNothing) {
  test::VirtualLine line{{"a6b", "ds5c1", "ds1000a"}};
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 3u);
  master.set_mailbox_timeout(20'000'000);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  const ProcessImageLayout layout = configure_process_data(master);
  CyclicTask task(master.transport(), layout, 3, 1'000'000, 0x1001);
  std::uint64_t seen = 0;
  task.on_outputs([&](std::span<std::uint8_t> image) { image[0] = static_cast<std::uint8_t>(seen); });
  task.on_inputs([&](std::span<std::uint8_t>) { ++seen; });
  task.run(10);  // warm-up: whatever the event loop or the link set up lazily
  const std::uint64_t before = g_allocations.load();
  ASSERT_GT(before, 0u) << "the counter sees allocations (scan, SII, layout)";
  task.run(200);
  EXPECT_EQ(g_allocations.load() - before, 0u);
  EXPECT_EQ(seen, 210u);
  EXPECT_EQ(task.stats().cycles, 210u);
}

// The same with an image that needs two frames per cycle (60 drives of the default mappings, 30
// bytes each): the pieces, their frames and the replies' bookkeeping are all set up before.
TEST(CyclicNoAllocation, SplitCyclesAllocateNothing) {
  static const char* const kMix[] = {"a6b", "ds5c1", "ds1000a"};
  std::vector<std::string> products;
  for (int i = 0; i < 60; ++i) products.emplace_back(kMix[i % 3]);
  test::VirtualLine line{products};
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 60u);
  master.set_mailbox_timeout(20'000'000);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  const ProcessImageLayout layout = configure_process_data(master);
  CyclicTask task(master.transport(), layout, 60, 1'000'000, 0x1001);
  ASSERT_GE(task.frames_per_cycle(), 2u);
  task.run(10);
  const std::uint64_t before = g_allocations.load();
  task.run(200);
  EXPECT_EQ(g_allocations.load() - before, 0u);
  EXPECT_EQ(task.stats().cycles, 210u);
  EXPECT_EQ(task.stats().lost_frames, 0u);
  EXPECT_EQ(task.stats().al_wkc, 60) << "frame 0's BRD came back from every slave";
}

}  // namespace
}  // namespace vdrive::master
