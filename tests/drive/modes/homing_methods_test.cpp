// Every standard homing method (1-14, 17-30, 33, 34, 35, 37) of every product, from two or three
// start positions, ends at the reference point the manuals' method texts define:
//   A6B L18735-L19332, DS5C1 L3570-L3673, DS1000A-EC L2766-L2956.
// Test line: negative limit x <= -1000, positive limit x >= 1000, index marks at 25 + 250 k, the
// home switch a window [100, 300] (methods 7-14, 23-30), active above 100 (3, 4, 19, 20) or below
// 100 (5, 6, 21, 22). Expected points are worked out by hand from that layout.
#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "tests/drive/modes/homing_test_axis.hpp"
#include "vdrive/drive/modes/homing_methods.hpp"

namespace vdrive::drive {
namespace {

using testing::AxisLayout;
using testing::HomingTestAxis;
using testing::kInf;

constexpr std::uint16_t kDone = (1u << 12) | (1u << 10);  // 011: homing completed (A6B L18196)
constexpr double kOffset = 10.0;                          // 607Ch in these tests

struct Case {
  std::int8_t method;
  AxisLayout layout;
  std::vector<double> starts;
  double reference;  // true position of the reference point
};

AxisLayout window() { return {-1000.0, 1000.0, {{100.0, 300.0}}}; }
AxisLayout above() { return {-2000.0, 2000.0, {{100.0, kInf}}}; }
AxisLayout below() { return {-2000.0, 2000.0, {{-kInf, 100.0}}}; }

std::vector<Case> cases() {
  const std::vector<double> limit_starts_neg = {-500.0, 600.0, -1100.0};  // -1100: on the limit
  const std::vector<double> limit_starts_pos = {-500.0, 600.0, 1100.0};
  const std::vector<double> win = {-500.0, 200.0, 600.0};                // left of, in, right of
  const std::vector<double> two = {-500.0, 500.0};
  return {
      {1, window(), limit_starts_neg, -975.0},  // first index above the NOT edge
      {2, window(), limit_starts_pos, 775.0},   // first index below the POT edge
      {3, above(), two, 25.0},
      {4, above(), two, 275.0},
      {5, below(), two, 275.0},
      {6, below(), two, 25.0},
      {7, window(), win, 25.0},     // index below the lower edge
      {8, window(), win, 275.0},    // index above the lower edge
      {9, window(), win, 275.0},    // index below the upper edge
      {10, window(), win, 525.0},   // index above the upper edge
      {11, window(), win, 525.0},
      {12, window(), win, 275.0},
      {13, window(), win, 275.0},
      {14, window(), win, 25.0},
      {17, window(), limit_starts_neg, -1000.0},
      {18, window(), limit_starts_pos, 1000.0},
      {19, above(), two, 100.0},
      {20, above(), two, 100.0},
      {21, below(), two, 100.0},
      {22, below(), two, 100.0},
      {23, window(), win, 100.0},
      {24, window(), win, 100.0},
      {25, window(), win, 300.0},
      {26, window(), win, 300.0},
      {27, window(), win, 300.0},
      {28, window(), win, 300.0},
      {29, window(), win, 100.0},
      {30, window(), win, 100.0},
  };
}

class HomingStandardMethods : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(HomingStandardMethods, EndsOnTheReferencePointWithStatus011) {
  const auto& [product, row] = GetParam();
  const Case c = cases()[static_cast<std::size_t>(row)];
  for (const double start : c.starts) {
    SCOPED_TRACE("product " + product + " method " + std::to_string(c.method) + " from x=" + std::to_string(start));
    HomingTestAxis axis(product, c.layout);
    axis.method(c.method);
    axis.set(0x607C, 0, static_cast<std::int64_t>(kOffset));
    axis.place(start);
    ASSERT_TRUE(axis.home());
    EXPECT_EQ(axis.bits(), kDone);
    EXPECT_EQ(axis.homes_found(), 1);
    // 6064h reads 607Ch at the reference point; the DS5C1 applies 607Ch only in 35/37 (L3504),
    // else the point reads 0 (L3376).
    const double value = product == "ds5c1" ? 0.0 : kOffset;
    EXPECT_NEAR(axis.true_of(value), c.reference, 0.5);
    // The axis stands near the point (servo-lock stop, A6B L17980).
    EXPECT_NEAR(axis.x(), c.reference, 3.0);
  }
}

std::string name(const ::testing::TestParamInfo<std::tuple<std::string, int>>& info) {
  return std::get<0>(info.param) + "_method" +
         std::to_string(cases()[static_cast<std::size_t>(std::get<1>(info.param))].method);
}

INSTANTIATE_TEST_SUITE_P(AllProducts, HomingStandardMethods,
                         ::testing::Combine(::testing::Values("a6b", "ds5c1", "ds1000a"),
                                            ::testing::Range(0, 28)),
                         name);

// 33 moves negative, 34 positive to the next index (DS5C1 L3667; CiA 402).
class HomingIndexMethods : public ::testing::TestWithParam<std::string> {};

TEST_P(HomingIndexMethods, NextIndexInTheMethodsDirection) {
  const std::string product = GetParam();
  struct Run {
    std::int8_t method;
    double start, reference;
  };
  for (const Run r : {Run{33, 400.0, 275.0}, Run{33, -100.0, -225.0}, Run{34, 400.0, 525.0}, Run{34, -100.0, 25.0}}) {
    SCOPED_TRACE(product + " method " + std::to_string(r.method) + " from " + std::to_string(r.start));
    HomingTestAxis axis(product, window());
    axis.method(r.method);
    axis.place(r.start);
    ASSERT_TRUE(axis.home());
    EXPECT_EQ(axis.bits(), kDone);
    EXPECT_NEAR(axis.true_of(0.0), r.reference, 1e-9);  // the index mark itself, exactly
  }
}

INSTANTIATE_TEST_SUITE_P(AllProducts, HomingIndexMethods, ::testing::Values("a6b", "ds5c1", "ds1000a"));

// 35/37: here is home, 6064h = 607Ch at once, no motion (A6B L19289-L19319, DS1000A-EC L2928-L2930),
// the DS5C1 applies 607Ch here (L3504); also outside Operation enabled (A6B L19313, DS5C1 L3525).
class HomingCurrentPosition : public ::testing::TestWithParam<std::string> {};

TEST_P(HomingCurrentPosition, PresetsWithoutMotionEvenWhenNotEnabled) {
  const std::string product = GetParam();
  for (const std::int8_t m : {std::int8_t{35}, std::int8_t{37}}) {
    for (const bool enabled : {true, false}) {
      for (const double start : {123.0, -50.0}) {
        SCOPED_TRACE(product + " method " + std::to_string(m) + (enabled ? " enabled" : " disabled"));
        HomingTestAxis axis(product, window());
        axis.method(m);
        axis.set(0x607C, 0, 7);
        axis.place(start);
        axis.tick(enabled ? 0x000F : 0x0007, enabled);
        axis.tick(enabled ? 0x001F : 0x0017, enabled);
        // bit 12 is 0 for about 2 ms after the start (A6B L18211-L18212, DS5C1 L3437).
        EXPECT_EQ(axis.bits() & (1u << 12), 0u);
        EXPECT_EQ(axis.homes_found(), 1);
        EXPECT_DOUBLE_EQ(axis.user_position(), 7.0);
        EXPECT_DOUBLE_EQ(axis.x(), start);
        for (int i = 0; i < 5; ++i) axis.tick(enabled ? 0x001F : 0x0017, enabled);
        EXPECT_EQ(axis.bits(), kDone);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllProducts, HomingCurrentPosition, ::testing::Values("a6b", "ds5c1", "ds1000a"));

TEST(HomingMethodTable, StandardMethodsOnlyAndReservedOnesAbsent) {
  for (int m = -128; m <= 127; ++m) {
    const bool standard = (m >= 1 && m <= 14) || (m >= 17 && m <= 30) || m == 33 || m == 34 || m == 35 || m == 37;
    EXPECT_EQ(find_standard_homing_method(static_cast<std::int8_t>(m)) != nullptr, standard) << m;
  }
  // 15, 16 reserved; 31, 32, 36 absent (A6B L17826-L17858).
  EXPECT_EQ(find_standard_homing_method(15), nullptr);
  EXPECT_EQ(find_standard_homing_method(36), nullptr);
}

}  // namespace
}  // namespace vdrive::drive
