// A line cut into parts for `vdrive run --processes N` (line_parts.hpp).
#include "vdrive/network/line_parts.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace vdrive::network {
namespace {

std::vector<std::size_t> counts(const std::vector<LinePart>& parts) {
  std::vector<std::size_t> out;
  std::size_t next = 0;
  for (const LinePart& p : parts) {
    EXPECT_EQ(p.first, next);  // consecutive, nothing left out
    next += p.count;
    out.push_back(p.count);
  }
  return out;
}

TEST(LineParts, PartsAreConsecutiveAndDifferByOneSlaveAtMost) {
  EXPECT_EQ(counts(split_line(3, 2)), (std::vector<std::size_t>{2, 1}));
  EXPECT_EQ(counts(split_line(200, 2)), (std::vector<std::size_t>{100, 100}));
  EXPECT_EQ(counts(split_line(10, 4)), (std::vector<std::size_t>{3, 3, 2, 2}));
  EXPECT_EQ(counts(split_line(5, 5)), (std::vector<std::size_t>{1, 1, 1, 1, 1}));
  EXPECT_EQ(counts(split_line(7, 1)), (std::vector<std::size_t>{7}));
}

TEST(LineParts, MorePartsThanSlavesOrNoneIsRefused) {
  try {
    split_line(2, 3);
    FAIL() << "3 parts of 2 slaves";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "the line has 2 slave(s); give 1 to 2");
  }
  EXPECT_THROW(split_line(2, 0), std::invalid_argument);
}

TEST(LineParts, EachSlaveIsInExactlyOnePart) {
  const std::vector<LinePart> parts = split_line(5, 2);  // slaves 0-2 | 3-4
  EXPECT_EQ(part_of(parts, 0), 0u);
  EXPECT_EQ(part_of(parts, 2), 0u);
  EXPECT_EQ(part_of(parts, 3), 1u);
  EXPECT_EQ(part_of(parts, 4), 1u);
  EXPECT_EQ(part_of(parts, 5), 2u);  // none
}

TEST(LineParts, APartIsNamedByItsNumberAndItsSlaves) {
  EXPECT_EQ(part_name(1, {2, 1}), "part 2 (slave 3)");
  EXPECT_EQ(part_name(2, {3, 2}), "part 3 (slaves 4-5)");
}

}  // namespace
}  // namespace vdrive::network
