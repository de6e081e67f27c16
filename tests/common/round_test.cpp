// round_to_int64 must give std::llround's answer for every input: half-way cases, the neighbours of
// half-way cases (where "add 0.5 and truncate" goes wrong), large and non-finite values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/round.hpp"

namespace vdrive {
namespace {

void expect_same(double x) { EXPECT_EQ(round_to_int64(x), std::llround(x)) << std::hexfloat << x; }

TEST(RoundToInt64, HalfWayCasesGoAwayFromZero) {
  for (double x : {0.5, 1.5, 2.5, -0.5, -1.5, -2.5, 1e9 + 0.5, -1e9 - 0.5}) expect_same(x);
  EXPECT_EQ(round_to_int64(2.5), 3);
  EXPECT_EQ(round_to_int64(-2.5), -3);
}

TEST(RoundToInt64, NeighboursOfHalfWayCases) {
  for (double h : {0.5, 1.5, 4503599627370495.5, -0.5, -7.5}) {
    expect_same(std::nextafter(h, 0.0));
    expect_same(std::nextafter(h, h * 2));
  }
  expect_same(0.49999999999999994);  // + 0.5 rounds up to 1.0 in double arithmetic
  expect_same(-0.0);
  expect_same(0.0);
}

TEST(RoundToInt64, LargeValuesAndTheEdgesOf2To52) {
  for (double x : {0x1p52, -0x1p52, std::nextafter(0x1p52, 0.0), 0x1p53 + 2, -0x1p62, 9.2e18}) expect_same(x);
}

TEST(RoundToInt64, RandomValuesAcrossMagnitudes) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-4, 60);
  for (int i = 0; i < 200000; ++i) expect_same(std::ldexp(mantissa(rng), exponent(rng)));
}

}  // namespace
}  // namespace vdrive
