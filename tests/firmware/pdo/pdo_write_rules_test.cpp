// SDO writes to 16xxh/1Axxh/1C12h/1C13h, per product rule, each abort once. Expected codes are the
// manuals': A6B abort table L4411-L4552 and 06010003h rules L7004-L7006/L7060-L7062; DS5C1
// 06010003h L5587/L5622; DS1000A-EC (no codes in its manual) the CiA 301 set.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <span>

#include "tests/firmware/pdo_test_bench.hpp"
#include "vdrive/firmware/pdo/pdo_write_rules.hpp"

namespace vdrive::firmware::pdo {
namespace {

using od::SdoAbort;
using test::ModuleBench;

std::array<std::uint8_t, 4> u32(std::uint32_t v) {
  return {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
          static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
}
std::array<std::uint8_t, 2> u16(std::uint16_t v) {
  return {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)};
}
std::array<std::uint8_t, 1> u8(std::uint8_t v) { return {v}; }

SdoAbort sdo_write(ModuleBench& b, std::uint16_t index, std::uint8_t sub,
                   std::span<const std::uint8_t> data) {
  return b.objects.write(index, sub, data, b.esm.state());
}

TEST(PdoWriteRules, A6bRemapInPreOpIsAccepted) {
  ModuleBench b("a6b");
  b.go(0x0002);
  ASSERT_EQ(b.esm.state(), ecat::AlState::PreOp);
  EXPECT_EQ(sdo_write(b, 0x1600, 0, u8(0)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1600, 1, u32(0x60400010)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1600, 2, u32(0x607A0020)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1600, 0, u8(2)), SdoAbort::Ok);
  EXPECT_EQ(b.value(0x1600, 0)[0], 2);
  EXPECT_EQ(sdo_write(b, 0x1C12, 0, u8(0)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1C12, 1, u16(0x1601)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1C12, 0, u8(1)), SdoAbort::Ok);
}

TEST(PdoWriteRules, A6bEntriesOnlyWhileCountIsZero) {
  ModuleBench b("a6b");
  b.go(0x0002);
  ASSERT_NE(b.value(0x1600, 0)[0], 0);  // factory mapping 1: 4 entries (L7346-L7354)
  EXPECT_EQ(sdo_write(b, 0x1600, 1, u32(0x60400010)), SdoAbort::SubindexCannotBeWritten);
}

TEST(PdoWriteRules, A6bOutsidePreOpIsRefusedWith06010003) {
  ModuleBench b("a6b");
  const PdoLimits limits = b.module.limits();
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::SafeOp, limits, 0x1C12, 0, u8(0)),
            SdoAbort::SubindexCannotBeWritten);
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::Op, limits, 0x1A00, 0, u8(0)),
            SdoAbort::SubindexCannotBeWritten);
}

TEST(PdoWriteRules, A6bJudgesMappabilityOnlyAtSafeOp) {
  // 06040041h is "not supported" by the A6B (L4411-L4552): the write is taken.
  ModuleBench b("a6b");
  b.go(0x0002);
  EXPECT_EQ(sdo_write(b, 0x1600, 0, u8(0)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1600, 1, u32(0x10000020)), SdoAbort::Ok);  // 1000h Device type
  EXPECT_EQ(sdo_write(b, 0x1600, 0, u8(1)), SdoAbort::Ok);
}

TEST(PdoWriteRules, AssignmentMustNameAMappingObjectOfItsDirection) {
  ModuleBench b("a6b");
  b.go(0x0002);
  EXPECT_EQ(sdo_write(b, 0x1C12, 0, u8(0)), SdoAbort::Ok);
  // The dictionary's own range (1600h-1603h) answers first over SDO ...
  EXPECT_EQ(sdo_write(b, 0x1C12, 1, u16(0x1A00)), SdoAbort::ValueTooHigh);
  // ... the rule itself, for dictionaries without that range: value range exceeded.
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, b.module.limits(), 0x1C12, 1, u16(0x1A00)),
            SdoAbort::ValueRangeExceeded);
}

// All three profiles judge mappings at PreOp->SafeOp (profile.yaml pdo_rules.checked_at_safeop):
// the write is taken and PS fails (pdo_process_data_test.cpp).
TEST(PdoWriteRules, ProfilesJudgeMappingsAtSafeOp) {
  ModuleBench b("ds5c1");
  EXPECT_FALSE(b.module.limits().mappable_checked_on_write);
  EXPECT_FALSE(b.module.limits().length_checked_on_write);
  b.go(0x0002);
  EXPECT_EQ(b.value(0x1600, 0)[0], 5);  // factory 1600h from the profile (L8613-L8617)
  EXPECT_EQ(sdo_write(b, 0x1600, 0, u8(0)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1600, 1, u32(0x10000020)), SdoAbort::Ok);
}

// A product that judges at the write (pdo_rules.checked_at_safeop: false) refuses a
// non-mappable object with 06040041h.
TEST(PdoWriteRules, CheckedOnWriteRefusesANonMappableObject) {
  ModuleBench b("ds5c1");  // 1601h/1A01h: empty (00h = 0) from the factory
  PdoLimits limits = b.module.limits();
  limits.mappable_checked_on_write = true;
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1A01, 1, u32(0x10000020)),
            SdoAbort::NotMappable);  // 1000h Device type
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1601, 1, u32(0x60410010)),
            SdoAbort::NotMappable);  // 6041h Statusword is TxPDO only
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1601, 1, u32(0x60400008)),
            SdoAbort::NotMappable);  // 6040h is 16 bits, not 8
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1601, 1, u32(0x60400010)),
            SdoAbort::Ok);
}

TEST(PdoWriteRules, CheckedOnWriteCountNeedsEntriesThatExist) {
  ModuleBench b("ds5c1");
  b.go(0x0002);
  PdoLimits limits = b.module.limits();
  limits.mappable_checked_on_write = true;
  EXPECT_EQ(sdo_write(b, 0x1601, 0, u8(0)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1601, 1, u32(0x60400010)), SdoAbort::Ok);
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1601, 0, u8(2)),
            SdoAbort::NotMappable);  // entry 02h is empty
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1601, 0, u8(1)), SdoAbort::Ok);
}

TEST(PdoWriteRules, Ds1000aOutsidePreOpIsAStateAbort) {
  ModuleBench b("ds1000a");
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::SafeOp, b.module.limits(), 0x1600, 0, u8(0)),
            SdoAbort::WrongState);
}

TEST(PdoWriteRules, Ds1000aAssignsOnePdo) {
  ModuleBench b("ds1000a");
  b.go(0x0002);
  EXPECT_EQ(sdo_write(b, 0x1C12, 0, u8(0)), SdoAbort::Ok);
  EXPECT_EQ(sdo_write(b, 0x1C12, 0, u8(2)), SdoAbort::ValueTooHigh);  // range 0-1 (L4673-L4684)
  EXPECT_EQ(sdo_write(b, 0x1C12, 0, u8(1)), SdoAbort::Ok);
}

TEST(PdoWriteRules, CheckedOnWriteRefusesATooLongMapping) {
  // DS1000A 1600h factory mapping: 6040h 16, 6060h 8, 607Ah 32, 6081h 32, 60FEh:01 32 = 15 bytes.
  // With an 8-byte limit, 00h = 5 exceeds it, 00h = 2 (3 bytes) does not.
  ModuleBench b("ds1000a");
  PdoLimits limits = b.module.limits();
  limits.length_checked_on_write = true;
  limits.rx.max_bytes = 8;
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1600, 0, u8(5)),
            SdoAbort::PdoLengthExceeded);
  EXPECT_EQ(judge_pdo_write(b.objects, ecat::AlState::PreOp, limits, 0x1600, 0, u8(2)), SdoAbort::Ok);
}

}  // namespace
}  // namespace vdrive::firmware::pdo
