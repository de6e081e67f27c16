// A process-RAM access of many bytes behaves as the same bytes accessed one at a time in ascending
// order: address_space.cpp hands a SyncManager every byte of an access that falls in its window at
// once. Checked on twin ESCs, one accessed in one go and one byte by byte, with random layouts
// (overlapping windows, mailbox and 3-buffer, both directions, windows past the end of process RAM)
// and random accesses from both sides; after every access the data, the working counter, process
// RAM, the SM registers and both event registers must agree.
#include <gtest/gtest.h>

#include <random>

#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

constexpr std::uint16_t kRamStart = 0x1000;
constexpr std::uint16_t kRamEnd = 0x3000;  // 8 KiB, the default
constexpr int kSmCount = 8;

EscConfig twin_config() {
  EscConfig c = default_config();
  c.sm_count = kSmCount;
  return c;
}

struct Twins {
  VirtualClock clock;
  Esc bulk{twin_config(), clock};
  Esc bytewise{twin_config(), clock};

  Result ecat(Esc& esc, std::uint8_t command, std::uint16_t ado, std::vector<std::uint8_t> d) {
    return send({&esc}, command, Frame::ap(0x1001, ado), std::move(d), clock.now());
  }
  void both_ecat(std::uint8_t command, std::uint16_t ado, std::vector<std::uint8_t> d) {
    ecat(bulk, command, ado, d);
    ecat(bytewise, command, ado, std::move(d));
  }
};

std::vector<std::uint8_t> sm_registers(std::uint16_t start, std::uint16_t len, std::uint8_t control,
                                       std::uint8_t activate) {
  return {static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8),
          static_cast<std::uint8_t>(len), static_cast<std::uint8_t>(len >> 8), control, 0, activate, 0};
}

void expect_same_state(const Esc& a, const Esc& b, int step) {
  for (std::uint32_t x = kRamStart; x < kRamEnd; ++x) {
    ASSERT_EQ(a.peek(static_cast<std::uint16_t>(x)), b.peek(static_cast<std::uint16_t>(x)))
        << "process RAM 0x" << std::hex << x << " after access " << std::dec << step;
  }
  for (std::uint16_t x = 0x0800; x < 0x0800 + 8 * kSmCount; ++x) {
    ASSERT_EQ(a.peek(x), b.peek(x)) << "SM register 0x" << std::hex << x << " after access " << std::dec << step;
  }
  for (std::uint16_t x : {0x0210, 0x0211, 0x0220, 0x0221, 0x0222, 0x0223}) {
    ASSERT_EQ(a.peek(x), b.peek(x)) << "event register 0x" << std::hex << x << " after access " << std::dec << step;
  }
  ASSERT_EQ(a.pdi_irq(), b.pdi_irq()) << "after access " << step;
}

class SmRunAccess : public ::testing::TestWithParam<unsigned> {};

TEST_P(SmRunAccess, OneAccessEqualsItsBytesInOrder) {
  std::mt19937 rng(GetParam());
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  Twins t;
  for (Esc* esc : {&t.bulk, &t.bytewise}) {
    send({esc}, cmd::APWR, Frame::ap(0, 0x0010), u16(0x1001), t.clock.now());
  }
  // Windows cluster in a small area so that they overlap; one may run past the end of RAM.
  constexpr std::uint8_t kControls[] = {0x26, 0x22, 0x64, 0x20, 0x24, 0x02};
  for (int n = 0; n < kSmCount; ++n) {
    const auto start = static_cast<std::uint16_t>(pick(0, 3) == 0 ? kRamEnd - pick(1, 24) : kRamStart + pick(0, 96));
    const auto len = static_cast<std::uint16_t>(pick(1, 40));
    const std::uint8_t control = kControls[pick(0, 5)];
    const auto activate = static_cast<std::uint8_t>(pick(0, 4) == 0 ? 0 : 1);
    t.both_ecat(cmd::FPWR, static_cast<std::uint16_t>(0x0800 + 8 * n), sm_registers(start, len, control, activate));
  }
  expect_same_state(t.bulk, t.bytewise, -1);

  for (int step = 0; step < 400; ++step) {
    const bool near_end = pick(0, 5) == 0;
    const auto address = static_cast<std::uint16_t>(near_end ? kRamEnd - pick(1, 40) : kRamStart + pick(0, 150));
    const auto size = static_cast<std::size_t>(pick(1, 64));
    const bool write = pick(0, 1) == 1;
    const bool pdi = pick(0, 1) == 1;
    std::vector<std::uint8_t> data(size);
    for (auto& b : data) b = static_cast<std::uint8_t>(pick(0, 255));

    std::vector<std::uint8_t> got_bulk, got_bytes(size);
    bool counted_bulk = false, counted_bytes = false;
    if (pdi) {
      if (write) {
        t.bulk.pdi_write(address, data);
        for (std::size_t i = 0; i < size; ++i)
          t.bytewise.pdi_write(static_cast<std::uint16_t>(address + i), std::span(data).subspan(i, 1));
      } else {
        got_bulk.resize(size);
        t.bulk.pdi_read(address, got_bulk);
        for (std::size_t i = 0; i < size; ++i)
          t.bytewise.pdi_read(static_cast<std::uint16_t>(address + i), std::span(got_bytes).subspan(i, 1));
      }
    } else {
      const std::uint8_t command = write ? cmd::FPWR : cmd::FPRD;
      const Result r = t.ecat(t.bulk, command, address, write ? data : std::vector<std::uint8_t>(size, 0));
      got_bulk = r.data;
      counted_bulk = r.wkc != 0;
      for (std::size_t i = 0; i < size; ++i) {
        const Result b = t.ecat(t.bytewise, command, static_cast<std::uint16_t>(address + i),
                                {write ? data[i] : std::uint8_t{0}});
        got_bytes[i] = b.data[0];
        counted_bytes = counted_bytes || b.wkc != 0;
      }
      EXPECT_EQ(counted_bulk, counted_bytes) << "working counter of access " << step;
    }
    if (!write) {
      EXPECT_EQ(got_bulk, got_bytes) << "data of access " << step;
    }
    expect_same_state(t.bulk, t.bytewise, step);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, SmRunAccess, ::testing::Range(1u, 41u));

}  // namespace
}  // namespace vdrive::esc::test
