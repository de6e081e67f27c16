// "Did you mean": edit distance with swaps, and the nearest candidate within a limit.
#include "common/nearest_word.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string_view>

namespace vdrive {
namespace {

TEST(NearestWord, EditsAreInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(edit_distance("duration", "duration"), 0u);
  EXPECT_EQ(edit_distance("duraton", "duration"), 1u);
  EXPECT_EQ(edit_distance("cps", "csp"), 1u) << "a swap of neighbours is one edit";
  EXPECT_EQ(edit_distance("cps", "pp"), 2u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(NearestWord, TheNearestWithinTheLimitOrNothing) {
  constexpr std::array<std::string_view, 4> modes = {"pp", "pv", "csp", "csv"};
  EXPECT_EQ(nearest_word("cps", modes), "csp");
  EXPECT_EQ(nearest_word("pw", modes), "pp") << "the first of equals";
  EXPECT_FALSE(nearest_word("torque", modes));
  EXPECT_FALSE(nearest_word("cqq", modes, 1));
}

}  // namespace
}  // namespace vdrive
