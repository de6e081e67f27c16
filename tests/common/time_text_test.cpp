#include "common/time_text.hpp"

#include <gtest/gtest.h>

namespace vdrive {
namespace {

TEST(TimeText, EveryUnit) {
  EXPECT_EQ(parse_time("40ns"), 40);
  EXPECT_EQ(parse_time("125us"), 125'000);
  EXPECT_EQ(parse_time("250ms"), 250'000'000);
  EXPECT_EQ(parse_time("1.5s"), 1'500'000'000);
  EXPECT_EQ(parse_time("2min"), 120'000'000'000);
  EXPECT_EQ(parse_time(" 3 ms "), 3'000'000);
  EXPECT_EQ(parse_time("0s"), 0);
}

TEST(TimeText, NumbersWithoutAUnitOrWithAWrongOneAreRefused) {
  EXPECT_FALSE(parse_time("250"));
  EXPECT_FALSE(parse_time("250 m"));
  EXPECT_FALSE(parse_time("-1ms"));
  EXPECT_FALSE(parse_time("ms"));
  EXPECT_FALSE(parse_time("1.2.3s"));
  EXPECT_FALSE(parse_time(""));
  EXPECT_FALSE(parse_time("99999999999999min"));
}

}  // namespace
}  // namespace vdrive
