// CachedExp gives std::exp's bits for every argument, repeated or not, NaN and infinities included.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "common/cached_exp.hpp"

namespace vdrive {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

TEST(CachedExp, SameBitsAsExpForEverySequence) {
  std::vector<double> xs = {0.0, -0.0, -0.125, -0.125, 1.0, -0.125, 710.0, -746.0,
                            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(), 0.0};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> d(-50.0, 5.0);
  for (int i = 0; i < 10'000; ++i) {
    const double x = d(rng);
    xs.push_back(x);
    if (i % 3 == 0) xs.push_back(x);  // the steady case: the same argument again
  }
  CachedExp cached;
  for (const double x : xs) {
    const double want = std::exp(x);
    const double got = cached(x);
    if (std::isnan(want)) {
      EXPECT_TRUE(std::isnan(got)) << x;
    } else {
      EXPECT_EQ(bits(got), bits(want)) << x;
    }
  }
}

TEST(CachedExp, FirstCallWithZeroIsOne) {
  CachedExp cached;
  EXPECT_EQ(cached(0.0), 1.0);
  EXPECT_EQ(cached(-1.0), std::exp(-1.0));
}

}  // namespace
}  // namespace vdrive
