// An integer entry's value from its bytes and the range of its type (vdrive/od/entry_value.hpp).
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "vdrive/od/entry_value.hpp"

namespace vdrive::od {
namespace {

TEST(EntryValue, SignedTypesAreSignExtendedFromTheirWidth) {
  EntryDesc i16;
  i16.type = DataType::Integer16;
  EXPECT_EQ(entry_integer(i16, std::vector<std::uint8_t>{0xFE, 0xFF}), -2);
  EntryDesc u16;
  u16.type = DataType::Unsigned16;
  EXPECT_EQ(entry_integer(u16, std::vector<std::uint8_t>{0xFE, 0xFF}), 0xFFFE);
  EntryDesc i64;
  i64.type = DataType::Integer64;
  EXPECT_EQ(entry_integer(i64, std::vector<std::uint8_t>(8, 0xFF)), -1);
  EXPECT_EQ(entry_integer(u16, std::vector<std::uint8_t>{}), 0);
}

TEST(EntryValue, IntegerRangesByWidthAndSign) {
  EXPECT_EQ(integer_range(8, true).min, -128);
  EXPECT_EQ(integer_range(8, true).max, 127);
  EXPECT_EQ(integer_range(16, false).max, 65535);
  EXPECT_EQ(integer_range(1, false).max, 1);
  EXPECT_EQ(integer_range(64, true).min, std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(integer_range(64, false).min, 0);
  EXPECT_EQ(integer_range(64, false).max, std::numeric_limits<std::int64_t>::max());
}

}  // namespace
}  // namespace vdrive::od
