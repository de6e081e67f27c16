#include "vdrive/drive/motion_ramp.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace vdrive::drive {
namespace {

TEST(MotionRamp, VelocityRampRespectsAccelerationAndDeceleration) {
  MotionState s{};
  const double dt = 1e-3;
  for (int i = 0; i < 100; ++i) s = ramp_velocity(s, 1000.0, 10000.0, 20000.0, dt);
  EXPECT_NEAR(s.velocity, 1000.0, 1e-9);       // reached after 0.1 s
  EXPECT_NEAR(s.position, 50.0, 1e-6);          // area of the ramp: 0.5 * 0.1 s * 1000
  int steps = 0;
  while (s.velocity > 0.0) {
    s = ramp_velocity(s, 0.0, 10000.0, 20000.0, dt);
    ++steps;
  }
  EXPECT_EQ(steps, 50);                         // 1000 / 20000 = 0.05 s
}

TEST(MotionRamp, TrapezoidEndsOnTargetWithoutOvershoot) {
  for (double target : {1000.0, -3.7, 12345.678, 0.5}) {
    MotionState s{};
    double max_pos = 0.0, min_pos = 0.0;
    int steps = 0;
    while ((s.position != target || s.velocity != 0.0) && steps < 1000000) {
      s = move_to(s, target, 500.0, 2000.0, 4000.0, 125e-6);
      max_pos = std::max(max_pos, s.position);
      min_pos = std::min(min_pos, s.position);
      EXPECT_LE(std::abs(s.velocity), 500.0 + 1e-9);
      ++steps;
    }
    EXPECT_EQ(s.position, target);
    EXPECT_EQ(s.velocity, 0.0);
    EXPECT_LE(max_pos, std::max(target, 0.0) + 1e-9);
    EXPECT_GE(min_pos, std::min(target, 0.0) - 1e-9);
  }
}

TEST(MotionRamp, TrapezoidBrakesFirstWhenMovingAway) {
  MotionState s{0.0, -100.0};
  double lowest = 0.0;
  for (int i = 0; i < 100000 && (s.position != 10.0 || s.velocity != 0.0); ++i) {
    s = move_to(s, 10.0, 100.0, 1000.0, 1000.0, 1e-3);
    lowest = std::min(lowest, s.position);
  }
  EXPECT_EQ(s.position, 10.0);
  EXPECT_NEAR(lowest, -5.0, 0.2);  // v^2 / 2a = 100^2 / 2000
}

}  // namespace
}  // namespace vdrive::drive
