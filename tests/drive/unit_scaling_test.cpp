#include "vdrive/drive/unit_scaling.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace vdrive::drive {
namespace {

TEST(UnitScaling, IncrementsPerUserFollowTheFactorGroup) {
  UnitScaling u;
  // DS1000-EC default: 16000 inc/rev, 6091h 1/1, feed 1000 per rev -> 16 inc per user unit.
  u.apply({16000, 1, 1, 1, 1000, 1, 0});
  EXPECT_DOUBLE_EQ(u.increments_per_user(), 16.0);
  EXPECT_DOUBLE_EQ(u.position_to_user(2.0 * std::numbers::pi), 1000.0);  // one motor turn
  // Gear 3:1 (motor turns per shaft turn), feed 10 mm = 10000 um per shaft turn.
  u.apply({8388608, 1, 3, 1, 10000, 1, 0});
  EXPECT_NEAR(u.increments_per_user(), 8388608.0 * 3.0 / 10000.0, 1e-9);
  EXPECT_NEAR(u.user_to_rpm(u.rpm_to_user(3000.0)), 3000.0, 1e-9);
  EXPECT_NEAR(u.rpm_to_user(60.0), 10000.0 / 3.0, 1e-9);  // 1 motor rev/s = 1/3 shaft rev
}

TEST(UnitScaling, PolarityInvertsEachQuantityItsBitNames) {
  UnitScaling u;
  u.apply({1000, 1, 1, 1, 1000, 1, 0xE0});
  EXPECT_DOUBLE_EQ(u.position_to_user(2.0 * std::numbers::pi), -1000.0);
  EXPECT_DOUBLE_EQ(u.velocity_to_user(2.0 * std::numbers::pi), -1000.0);
  EXPECT_DOUBLE_EQ(u.torque_sign(), -1.0);
  u.apply({1000, 1, 1, 1, 1000, 1, 0x80});
  EXPECT_DOUBLE_EQ(u.position_sign(), -1.0);
  EXPECT_DOUBLE_EQ(u.velocity_to_user(1.0) > 0.0, true);
  u.apply({1000, 1, 1, 1, 1000, 1, 0x40}, /*torque_follows_velocity=*/true);
  EXPECT_DOUBLE_EQ(u.torque_sign(), -1.0);
}

TEST(UnitScaling, ZeroEncoderIncrementsMeanTwoToThe32) {
  UnitScaling u;
  u.apply({0, 1, 1, 1, 1, 1, 0});
  EXPECT_DOUBLE_EQ(u.increments_per_motor_rev(), 4294967296.0);
}

}  // namespace
}  // namespace vdrive::drive
