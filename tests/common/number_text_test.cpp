// Whole numbers as users write them: decimal or 0x hex, nothing else.
#include "common/number_text.hpp"

#include <gtest/gtest.h>

namespace vdrive {
namespace {

TEST(NumberText, DecimalAndHex) {
  EXPECT_EQ(parse_unsigned("24576"), 24576u);
  EXPECT_EQ(parse_unsigned("0x6000"), 0x6000u);
  EXPECT_EQ(parse_unsigned("0X1a"), 0x1Au);
  EXPECT_EQ(parse_unsigned("18446744073709551615"), UINT64_MAX);
}

TEST(NumberText, AnythingElseIsNotANumber) {
  EXPECT_FALSE(parse_unsigned(""));
  EXPECT_FALSE(parse_unsigned("0x"));
  EXPECT_FALSE(parse_unsigned("-1"));
  EXPECT_FALSE(parse_unsigned("12a"));
  EXPECT_FALSE(parse_unsigned("6000h"));
  EXPECT_FALSE(parse_unsigned("18446744073709551616"));
}

}  // namespace
}  // namespace vdrive
