// Encoder quantisation, wrap and index, with expected counts stated from the definition
// counts = floor(angle / 2pi * cpr).
#include <gtest/gtest.h>

#include <cmath>

#include "plant/encoder.hpp"
#include "plant/plant.hpp"
#include "tests/plant/plant_test_util.hpp"

namespace vdrive::plant {
namespace {

double angle_of(double counts, std::uint32_t cpr) { return counts * 2 * M_PI / cpr; }

TEST(Encoder, QuantisationIsExactInTheMiddleAndAtTheEdgesOfEveryCount) {
  EncoderSpec s{.counts_per_rev = 10000, .absolute = true, .multiturn_bits = 16};
  Encoder e(s, 0.0);
  for (std::int64_t k = -25000; k <= 25000; k += 7) {
    e.update(angle_of(k + 0.5, s.counts_per_rev));
    ASSERT_EQ(e.reading().counts, k);
    e.update(angle_of(k + 0.999, s.counts_per_rev));
    ASSERT_EQ(e.reading().counts, k);
    e.update(angle_of(k + 0.001, s.counts_per_rev));
    ASSERT_EQ(e.reading().counts, k);
  }
}

TEST(Encoder, SingleTurnAbsoluteKeepsOnlyThePositionInTheTurn) {
  EncoderSpec s{.counts_per_rev = 4096, .absolute = true, .multiturn_bits = 0};
  Encoder e(s, 0.0);
  e.update(angle_of(3 * 4096 + 100.5, 4096));
  EXPECT_EQ(e.reading().single_turn, 100u);
  EXPECT_EQ(e.reading().turns, 0);
  EXPECT_EQ(e.reading().counts, 100);
  e.update(angle_of(-1.5, 4096));
  EXPECT_EQ(e.reading().counts, 4094);
}

TEST(Encoder, MultiTurnCounterWrapsAtItsBitWidth) {
  EncoderSpec s{.counts_per_rev = 1000, .absolute = true, .multiturn_bits = 4};  // turns -8..7
  Encoder e(s, 0.0);
  e.update(angle_of(7 * 1000 + 10.5, 1000));
  EXPECT_EQ(e.reading().turns, 7);
  EXPECT_EQ(e.reading().counts, 7010);
  e.update(angle_of(8 * 1000 + 10.5, 1000));
  EXPECT_EQ(e.reading().turns, -8);
  EXPECT_EQ(e.reading().counts, -8000 + 10);
  e.update(angle_of(-1000 + 0.5, 1000));
  EXPECT_EQ(e.reading().turns, -1);
}

TEST(Encoder, IncrementalCountsFromZeroAtPowerOn) {
  EncoderSpec s{.counts_per_rev = 2000, .absolute = false, .multiturn_bits = 0};
  Encoder e(s, angle_of(12345.5, 2000));
  EXPECT_EQ(e.reading().counts, 0);
  e.update(angle_of(12345.5 + 300, 2000));
  EXPECT_EQ(e.reading().counts, 300);
  e.update(angle_of(12345.5 - 2500, 2000));
  EXPECT_EQ(e.reading().counts, -2500);
}

TEST(Encoder, IndexPulseOncePerTurnAtTheIndexAngle) {
  EncoderSpec s{.counts_per_rev = 1000, .absolute = true, .multiturn_bits = 16, .index_angle_rad = angle_of(250, 1000)};
  Encoder e(s, 0.0);
  EXPECT_FALSE(e.reading().index_passed);
  e.update(angle_of(249.5, 1000));
  EXPECT_FALSE(e.reading().index_passed);
  e.update(angle_of(250.5, 1000));
  EXPECT_TRUE(e.reading().index_passed);
  EXPECT_EQ(e.reading().index_counts, 250);
  e.update(angle_of(900, 1000));
  EXPECT_FALSE(e.reading().index_passed);
  e.update(angle_of(1300, 1000));  // next turn's mark
  EXPECT_TRUE(e.reading().index_passed);
  EXPECT_EQ(e.reading().index_counts, 1250);
  e.update(angle_of(1200, 1000));  // backwards over it again
  EXPECT_TRUE(e.reading().index_passed);
  EXPECT_EQ(e.reading().index_counts, 1250);
}

TEST(Encoder, PlantFeedbackIsTheQuantisedMotorAngleAtEveryStep) {
  Plant p(test::rotary(3e-4));
  p.command(0, test::torque(0.05));
  std::int64_t last = 0;
  for (int i = 0; i < 2000; ++i) {
    p.step();
    const AxisFeedback& f = p.feedback(0);
    ASSERT_EQ(f.encoder.counts, static_cast<std::int64_t>(std::floor(f.motor_angle_rad / (2 * M_PI) * 10000)));
    ASSERT_GE(f.encoder.counts, last);
    last = f.encoder.counts;
  }
  EXPECT_GT(last, 10000);  // more than a turn
}

}  // namespace
}  // namespace vdrive::plant
