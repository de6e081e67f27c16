// The frame path, the PDI and tick() allocate nothing after construction. Counts calls of the
// global operator new in this test binary while a busy cycle runs.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "tests/esc_model/esc_test_util.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace vdrive::esc::test {
namespace {

TEST_F(EscTest, CyclicTrafficAllocatesNothing) {
  set_station();
  fpwr(0x0800, sm_regs(0x1000, 32, 0x26));
  fpwr(0x0808, sm_regs(0x1080, 32, 0x22));
  fpwr(0x0810, sm_regs(0x1100, 8, 0x64));
  fpwr(0x0818, sm_regs(0x1180, 8, 0x20));
  fpwr(0x0600, {0x00, 0x00, 0x01, 0x00, 8, 0, 0, 7, 0x00, 0x11, 0, 2, 1, 0, 0, 0});
  fpwr(0x0610, {0x08, 0x00, 0x01, 0x00, 8, 0, 0, 7, 0x80, 0x11, 0, 1, 1, 0, 0, 0});
  fpwr(0x0620, {0x10, 0x00, 0x01, 0x00, 1, 0, 3, 3, 0x0D, 0x08, 3, 1, 1, 0, 0, 0});

  Frame cyclic;
  const auto lrw = cyclic.add(cmd::LRW, 0x10000, std::vector<std::uint8_t>(17, 0x11));
  cyclic.add(cmd::FPRD, Frame::ap(0x1001, 0x0130), std::vector<std::uint8_t>(6, 0));
  cyclic.add(cmd::ARMW, Frame::ap(0, 0x0910), std::vector<std::uint8_t>(8, 0));
  cyclic.add(cmd::BWR, Frame::ap(0, 0x0900), std::vector<std::uint8_t>(4, 0));
  cyclic.add(cmd::FPWR, Frame::ap(0x1001, 0x1000), std::vector<std::uint8_t>(32, 0x22));
  cyclic.add(cmd::FPRD, Frame::ap(0x1001, 0x1080), std::vector<std::uint8_t>(32, 0));
  cyclic.add(cmd::FPRD, Frame::ap(0x1001, 0x0502), std::vector<std::uint8_t>(8, 0));
  std::vector<std::uint8_t> bad = {0xFF, 0x17, 0x00};
  std::uint8_t buf[32] = {};
  FrameTiming timing;

  const long before = g_allocations.load();
  for (int i = 0; i < 100; ++i) {
    clock.advance(1'000'000);
    timing.port0_rx = clock.now();
    ASSERT_TRUE(esc->process_frame(cyclic.pdu(), timing));
    esc->process_frame(bad, timing);
    esc->pdi_read(0x0220, std::span<std::uint8_t>(buf, 4));
    esc->pdi_read(0x1000, buf);
    esc->pdi_read(0x1100, std::span<std::uint8_t>(buf, 8));
    esc->pdi_write(0x1180, std::span<const std::uint8_t>(buf, 8));
    esc->pdi_write(0x1080, buf);
    esc->tick(clock.now());
    (void)esc->next_deadline();
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(cyclic.wkc(lrw), 100 * 3);  // LRW answered every time (read + write)
}

}  // namespace
}  // namespace vdrive::esc::test
