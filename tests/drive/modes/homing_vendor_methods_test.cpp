// The vendor homing methods (6098h < 0) each product lists, on the test line with hard stops at
// -700 and +700 and index marks at 25 + 250 k:
//   DS1000A-EC -1/-2 push negative/positive until the torque limit holds for 2142h ms, then the
//   first index in the reverse direction; -3/-4 home where the torque was detected (L2957-L2967).
//   DS5C1 -1/-2 push forward/backward at 6099h-02h until P9-17 torque at under P9-16 speed for
//   P9-18 ms, then P7-20 index pulses back and the P9-19/P9-20 distance (L3549-L3568); the point
//   reads 0, 607Ch acts only in 35/37 (L3504).
//   A6B -1..-4 are "manufacturer use" with no documented sequence (L17864-L17870): a homing error.
#include <gtest/gtest.h>

#include <string>

#include "tests/drive/modes/homing_test_axis.hpp"

namespace vdrive::drive {
namespace {

using testing::AxisLayout;
using testing::HomingTestAxis;

constexpr std::uint16_t kDone = (1u << 12) | (1u << 10);
constexpr std::uint16_t kErrorStopped = (1u << 13) | (1u << 10);

AxisLayout hard_stops() {
  AxisLayout l;
  l.hard_stop_low = -700.0;
  l.hard_stop_high = 700.0;
  return l;
}

struct VendorRun {
  std::int8_t method;
  double reference;  // true position of the reference point
};

TEST(HomingVendorMethods, Ds1000aTorqueLimitMethodsEndAtTheStopOrTheNextIndex) {
  for (const VendorRun r : {VendorRun{-1, -475.0}, VendorRun{-2, 525.0}, VendorRun{-3, -700.0}, VendorRun{-4, 700.0}}) {
    SCOPED_TRACE("method " + std::to_string(r.method));
    HomingTestAxis axis("ds1000a", hard_stops());
    axis.method(r.method);
    axis.set(0x607C, 0, 10);
    axis.place(100.0);
    ASSERT_TRUE(axis.home());
    EXPECT_EQ(axis.bits(), kDone);
    EXPECT_EQ(axis.homes_found(), 1);
    EXPECT_NEAR(axis.true_of(10.0), r.reference, 0.5);
    EXPECT_GT(axis.max_torque_limit_seen(), 0.0) << "the push runs under a torque limit";
  }
}

TEST(HomingVendorMethods, Ds5c1HardStopMethodsEndOnTheIndexBackFromTheStop) {
  for (const VendorRun r : {VendorRun{-1, 525.0}, VendorRun{-2, -475.0}}) {
    SCOPED_TRACE("method " + std::to_string(r.method));
    HomingTestAxis axis("ds5c1", hard_stops());
    axis.method(r.method);
    axis.set(0x607C, 0, 10);
    axis.set(0x2913, 0, 0);  // P9-19/P9-20: no extra distance after the index
    axis.set(0x2914, 0, 0);
    axis.set(0x2714, 0, 1);  // P7-20: one index pulse back
    axis.place(100.0);
    ASSERT_TRUE(axis.home());
    EXPECT_EQ(axis.bits(), kDone);
    EXPECT_NEAR(axis.true_of(0.0), r.reference, 0.5) << "the point reads 0, not 607Ch";
  }
}

TEST(HomingVendorMethods, Ds5c1FixedDistanceAfterTheIndex) {
  HomingTestAxis axis("ds5c1", hard_stops());
  axis.method(-1);
  axis.set(0x2913, 0, 100);  // P9-19: 100 pulses
  axis.set(0x2914, 0, 0);
  axis.set(0x2714, 0, 1);
  axis.place(100.0);
  ASSERT_TRUE(axis.home());
  EXPECT_EQ(axis.bits(), kDone);
  EXPECT_NEAR(axis.true_of(0.0), 425.0, 0.5);  // index at 525, then 100 further back
}

TEST(HomingVendorMethods, A6bManufacturerMethodsAreAHomingError) {
  for (const std::int8_t m : {std::int8_t{-1}, std::int8_t{-4}}) {
    HomingTestAxis axis("a6b", hard_stops());
    axis.method(m);
    axis.place(100.0);
    axis.home(1.0);
    EXPECT_EQ(axis.bits(), kErrorStopped) << int(m);
    EXPECT_EQ(axis.homes_found(), 0);
    EXPECT_DOUBLE_EQ(axis.x(), 100.0) << "no motion";
  }
}

}  // namespace
}  // namespace vdrive::drive
