// Process data end to end on a real ESC: SM2/SM3 and FMMUs set up by hand, LRW frames carry the
// outputs into the mapped objects and the inputs out of them; the PreOp->SafeOp checks answer
// with the manual's AL status codes (A6B 8-1 table L32567-L32645: Err81.7 001Dh/001Eh, Err85.0
// 0024h, Err85.1 0025h, Err81.4 001Fh, Err80.4 001Bh); the cyclic path allocates nothing.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "tests/firmware/pdo_test_bench.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::firmware::pdo {
namespace {

using test::ModuleBench;

constexpr std::uint16_t kPreOp = 0x0002, kSafeOp = 0x0004, kOp = 0x0008, kAck = 0x0010;

void put(std::span<std::uint8_t> to, std::uint32_t value) {
  for (std::size_t i = 0; i < to.size(); ++i) to[i] = static_cast<std::uint8_t>(value >> (8 * i));
}
std::uint32_t get(std::span<const std::uint8_t> from) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < from.size() && i < 4; ++i) v |= static_cast<std::uint32_t>(from[i]) << (8 * i);
  return v;
}

// A6B factory mapping 1 (L7346-L7374): RxPDO 1600h 9 bytes, TxPDO 1A00h 23 bytes.
constexpr std::uint16_t kA6bOut = 9, kA6bIn = 23;

class A6bProcessData : public ::testing::Test {
protected:
  A6bProcessData() : b("a6b"), lrw(test::WireBench::frame(test::kLrw, test::kLogicalOutputs, kA6bOut + kA6bIn)) {}

  void to_safeop() {
    b.mailbox_layout();
    b.go(kPreOp);
    ASSERT_EQ(b.esm.state(), ecat::AlState::PreOp);
    b.process_data_layout(kA6bOut, kA6bIn);
    b.go(kSafeOp);
    ASSERT_EQ(b.esm.state(), ecat::AlState::SafeOp) << std::hex << b.esm.error_code();
  }
  std::span<std::uint8_t> outputs() { return test::WireBench::data_of(lrw).subspan(0, kA6bOut); }
  std::span<std::uint8_t> inputs() { return test::WireBench::data_of(lrw).subspan(kA6bOut, kA6bIn); }

  ModuleBench b;
  std::vector<std::uint8_t> lrw;
};

TEST_F(A6bProcessData, OutputsReachTheObjectsOnlyInOp) {
  to_safeop();
  // 6040h 16, 6060h 8, 607Ah 32, 60B8h 16, packed without gaps.
  put(outputs().subspan(0, 2), 0x000F);
  put(outputs().subspan(2, 1), 8);
  put(outputs().subspan(3, 4), 0x12345678);
  put(outputs().subspan(7, 2), 0x0011);
  EXPECT_EQ(b.run(lrw), 3);  // LRW: read (+1) and write (+2) FMMUs of one slave
  EXPECT_EQ(get(b.value(0x6040, 0)), 0u) << "outputs are not valid in SafeOp";

  b.go(kOp);
  ASSERT_EQ(b.esm.state(), ecat::AlState::Op);
  EXPECT_EQ(b.run(lrw), 3);
  EXPECT_EQ(get(b.value(0x6040, 0)), 0x000Fu);
  EXPECT_EQ(get(b.value(0x6060, 0)), 8u);
  EXPECT_EQ(get(b.value(0x607A, 0)), 0x12345678u);
  EXPECT_EQ(get(b.value(0x60B8, 0)), 0x0011u);
  EXPECT_TRUE(b.module.outputs_valid());
}

// The application (the CiA 402 drive) is told which objects the RxPDO carries when the mapping
// becomes effective, so it never reads 1C12h and the mapping objects itself.
TEST_F(A6bProcessData, TheApplicationHearsTheOutputMappingAtSafeOp) {
  std::vector<std::pair<std::uint16_t, std::uint8_t>> heard;
  int calls = 0;
  b.module.on_outputs_mapped([&](const ResolvedMapping& rx) {
    ++calls;
    heard.clear();
    for (int i = 0; i < rx.count; ++i)
      if (const od::EntryDesc* e = rx.items[static_cast<std::size_t>(i)].entry) heard.emplace_back(e->index, e->subindex);
  });
  b.mailbox_layout();
  b.go(kPreOp);
  EXPECT_EQ(calls, 0) << "no mapping is in effect before SafeOp";
  to_safeop();
  EXPECT_EQ(calls, 1);
  const std::vector<std::pair<std::uint16_t, std::uint8_t>> factory{{0x6040, 0}, {0x6060, 0}, {0x607A, 0}, {0x60B8, 0}};
  EXPECT_EQ(heard, factory);
}

TEST_F(A6bProcessData, InputsAppearInTheFrameFromSafeOp) {
  b.mailbox_layout();
  b.go(kPreOp);
  put(b.value(0x6041, 0), 0x0237);
  put(b.value(0x6064, 0), 0xCAFE0001);
  b.process_data_layout(kA6bOut, kA6bIn);
  b.go(kSafeOp);
  ASSERT_EQ(b.esm.state(), ecat::AlState::SafeOp);
  EXPECT_EQ(b.run(lrw), 3);
  // 603Fh 16, 6041h 16, 6061h 8, 6064h 32, ...
  EXPECT_EQ(get(inputs().subspan(2, 2)), 0x0237u);
  EXPECT_EQ(get(inputs().subspan(5, 4)), 0xCAFE0001u);

  // A new value is gathered after the master's next outputs and read by the frame after.
  put(b.value(0x6064, 0), 0x00000042);
  b.run(lrw);
  b.run(lrw);
  EXPECT_EQ(get(inputs().subspan(5, 4)), 0x42u);
}

TEST_F(A6bProcessData, CyclicPathAllocatesNothing) {
  to_safeop();
  b.go(kOp);
  ASSERT_EQ(b.esm.state(), ecat::AlState::Op);
  b.run(lrw);  // warm up
  const long before = vdrive::test::allocation_count();
  for (int i = 0; i < 200; ++i) {
    outputs()[0] = static_cast<std::uint8_t>(i);
    b.run(lrw);
  }
  EXPECT_EQ(vdrive::test::allocation_count(), before);
  EXPECT_EQ(b.value(0x6040, 0)[0], 199);
}

TEST_F(A6bProcessData, WatchdogExpiryInOpFallsToSafeOpAndRecovers) {
  to_safeop();
  b.go(kOp);
  b.run(lrw);  // SM2 written: the watchdog (SM2 control bit 6) starts, reset time 100 ms
  b.advance(50'000'000);
  b.run(lrw);
  b.advance(99'000'000);
  EXPECT_EQ(b.esm.state(), ecat::AlState::Op) << "retriggered in time";
  b.advance(2'000'000);
  EXPECT_EQ(b.esm.state(), ecat::AlState::SafeOp);
  EXPECT_TRUE(b.esm.error());
  EXPECT_EQ(b.esm.error_code(), 0x001B);  // Err80.4
  EXPECT_FALSE(b.module.outputs_valid());

  // Recovery: the master acknowledges, sends outputs again and requests Op.
  b.go(kSafeOp | kAck);
  EXPECT_FALSE(b.esm.error());
  b.run(lrw);
  b.go(kOp);
  EXPECT_EQ(b.esm.state(), ecat::AlState::Op);
  outputs()[0] = 0x07;
  b.run(lrw);
  EXPECT_EQ(b.value(0x6040, 0)[0], 0x07);
}

// ---- PreOp -> SafeOp checks ------------------------------------------------------------------

class A6bSafeOpCheck : public ::testing::Test {
protected:
  A6bSafeOpCheck() : b("a6b") {
    b.mailbox_layout();
    b.go(kPreOp);
  }
  void expect_refused(std::uint16_t code) {
    b.go(kSafeOp);
    EXPECT_EQ(b.esm.state(), ecat::AlState::PreOp);
    EXPECT_TRUE(b.esm.error());
    EXPECT_EQ(b.esm.error_code(), code);
  }
  void write(std::uint16_t index, std::uint8_t sub, std::uint32_t value, std::size_t size) {
    std::array<std::uint8_t, 4> bytes{};
    put(std::span<std::uint8_t>(bytes.data(), size), value);
    ASSERT_EQ(b.objects.write(index, sub, std::span<const std::uint8_t>(bytes.data(), size),
                              b.esm.state()),
              od::SdoAbort::Ok)
        << std::hex << index << ":" << int{sub};
  }
  ModuleBench b;
};

TEST_F(A6bSafeOpCheck, Sm2LengthNotTheRxPdoSize) {
  b.process_data_layout(kA6bOut + 1, kA6bIn);
  expect_refused(0x001D);
}

TEST_F(A6bSafeOpCheck, Sm3LengthNotTheTxPdoSize) {
  b.process_data_layout(kA6bOut, kA6bIn - 1);
  expect_refused(0x001E);
}

TEST_F(A6bSafeOpCheck, Sm2WrongDirection) {
  b.process_data_layout(kA6bOut, kA6bIn);
  b.sm(2, b.product.sync_managers[2].start, kA6bOut, 0x20, true);  // master would read it
  expect_refused(0x001D);
}

TEST_F(A6bSafeOpCheck, Sm3OddStart) {
  b.process_data_layout(kA6bOut, kA6bIn);
  b.sm(3, 0x1601, kA6bIn, 0x20, true);
  expect_refused(0x001E);
}

TEST_F(A6bSafeOpCheck, TxPdoOver32Bytes) {
  // 1A00h (23 B) + 1A01h (25 B) = 48 bytes > 32 (Err85.0, L33625-L33643).
  write(0x1C13, 0, 0, 1);
  write(0x1C13, 1, 0x1A00, 2);
  write(0x1C13, 2, 0x1A01, 2);
  write(0x1C13, 0, 2, 1);
  b.process_data_layout(kA6bOut, 48);
  expect_refused(0x0024);
}

TEST_F(A6bSafeOpCheck, RxPdoWithANonMappableObject) {
  write(0x1600, 0, 0, 1);
  write(0x1600, 1, 0x10000020, 4);  // 1000h Device type: not mappable (taken by SDO, L4411-L4552)
  write(0x1600, 0, 1, 1);
  b.process_data_layout(4, kA6bIn);
  expect_refused(0x0025);
}

TEST_F(A6bSafeOpCheck, WatchdogShorterThanTwoMillisecondsInFreeRun) {
  b.process_data_layout(kA6bOut, kA6bIn);
  b.write_u16(0x0420, 10);  // 10 x 100 us = 1 ms < 2 ms (Err81.4, L33447-L33481)
  expect_refused(0x001F);
  b.go(kPreOp | kAck);
  b.write_u16(0x0420, 20);  // 2 ms: accepted
  b.go(kSafeOp);
  EXPECT_EQ(b.esm.state(), ecat::AlState::SafeOp);
}

TEST_F(A6bSafeOpCheck, RemappedOutputsTakeEffectAtSafeOp) {
  write(0x1600, 0, 0, 1);
  write(0x1600, 1, 0x607A0020, 4);  // target position only
  write(0x1600, 0, 1, 1);
  b.process_data_layout(4, kA6bIn);
  b.go(kSafeOp);
  ASSERT_EQ(b.esm.state(), ecat::AlState::SafeOp) << std::hex << b.esm.error_code();
  EXPECT_EQ(b.module.output_bytes(), 4);
  b.go(kOp);
  std::vector<std::uint8_t> lrw = test::WireBench::frame(test::kLrw, test::kLogicalOutputs, 4 + kA6bIn);
  put(test::WireBench::data_of(lrw).subspan(0, 4), 0x00ABCDEF);
  EXPECT_EQ(b.run(lrw), 3);
  EXPECT_EQ(get(b.value(0x607A, 0)), 0x00ABCDEFu);
}

// ---- an SM2 the master enables while 1C12h assigns nothing (issue 22 item 12) ----------------
// Per product (docs/process-data.md): SM2 running with a length is refused by every one (the
// length rule: A6B L33564-L33566, DS5C1 L7129-L7133, ETG SSC for the DS1000A-EC); SM2 enabled
// with length 0 by the A6B (L4907, L4974) and the DS1000A-EC (ETG SSC), not by the DS5C1.

struct EmptyOutputsCase {
  const char* product;
  std::uint16_t inputs;   // factory TxPDO size
  bool refuses_enabled_length_0;
};

void PrintTo(const EmptyOutputsCase& c, std::ostream* os) { *os << c.product; }

class EmptyOutputs : public ::testing::TestWithParam<EmptyOutputsCase> {
protected:
  EmptyOutputs() : b(GetParam().product) {
    b.mailbox_layout();
    b.go(kPreOp);
    const std::array<std::uint8_t, 1> none{0};
    EXPECT_EQ(b.objects.write(0x1C12, 0, none, b.esm.state()), od::SdoAbort::Ok);
    b.process_data_layout(0, GetParam().inputs);
  }
  void sm2(std::uint16_t length, bool enabled) {
    const profile::SyncManagerSpec& s2 = b.product.sync_managers[2];
    b.sm(2, s2.start, length, s2.control, enabled);
  }
  ModuleBench b;
};

TEST_P(EmptyOutputs, Sm2DisabledWithLengthZeroReachesSafeOp) {
  b.go(kSafeOp);
  EXPECT_EQ(b.esm.state(), ecat::AlState::SafeOp) << std::hex << b.esm.error_code();
  EXPECT_EQ(b.module.output_bytes(), 0);
}

TEST_P(EmptyOutputs, Sm2RunningWithALengthIsRefusedWith001Dh) {
  sm2(9, true);
  b.go(kSafeOp);
  EXPECT_EQ(b.esm.state(), ecat::AlState::PreOp);
  EXPECT_TRUE(b.esm.error());
  EXPECT_EQ(b.esm.error_code(), 0x001D);
}

TEST_P(EmptyOutputs, Sm2EnabledWithLengthZeroAsTheProductDecides) {
  sm2(0, true);
  b.go(kSafeOp);
  if (GetParam().refuses_enabled_length_0) {
    EXPECT_EQ(b.esm.state(), ecat::AlState::PreOp);
    EXPECT_EQ(b.esm.error_code(), 0x001D);
  } else {
    EXPECT_EQ(b.esm.state(), ecat::AlState::SafeOp) << std::hex << b.esm.error_code();
  }
}

INSTANTIATE_TEST_SUITE_P(Products, EmptyOutputs,
                         ::testing::Values(EmptyOutputsCase{"a6b", kA6bIn, true},
                                           EmptyOutputsCase{"ds5c1", 13, false},
                                           EmptyOutputsCase{"ds1000a", 17, true}),
                         [](const ::testing::TestParamInfo<EmptyOutputsCase>& info) {
                           return std::string(info.param.product);
                         });

}  // namespace
}  // namespace vdrive::firmware::pdo
