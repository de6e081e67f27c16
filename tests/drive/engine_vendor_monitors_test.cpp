// Vendor monitor objects kept live by the drive (profile drive.monitors): the DS5C1's U0 group,
// 3000h + n = U0-n (xinje-ds5c1-user-manual.zh.md L5787-L5790), in the units of App. 1.3
// (L9017-L9066), current with 606Ch/6074h/6077h after every control step. The objects are typed
// U16 (the manual gives no type), so a negative value reads as its 16-bit two's complement.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

constexpr std::uint16_t kU0Speed = 0x3000, kU0SpeedCommand = 0x3001, kU0TorqueCommand = 0x3002,
                        kU0TorqueFeedback = 0x3007, kU0TorqueCurrent = 0x3012;

// The U16 monitor read as the signed 16-bit value the drive put there.
int u0(const EngineBench& b, std::uint16_t index) { return static_cast<std::int16_t>(b.get(index)); }

// U0-00 motor speed and U0-01 speed command in r/min (L9021, L9022), forwards and backwards.
TEST(Ds5c1U0Monitors, SpeedAndSpeedCommandInRpm) {
  EngineBench b("ds5c1");
  b.set(0x6083, 0, std::llround(20 * b.per_rev()));
  b.set(0x6084, 0, std::llround(20 * b.per_rev()));
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  EXPECT_EQ(b.get(kU0Speed), 0);
  b.set(0x60FF, 0, std::llround(b.user_speed(300)));
  b.run(1000 * kMs);
  EXPECT_NEAR(u0(b, kU0Speed), 300, 3) << b.diag();
  EXPECT_NEAR(u0(b, kU0Speed), b.motor_rpm(), 1.5) << "the motor's own speed";
  EXPECT_EQ(u0(b, kU0SpeedCommand), 300);
  b.set(0x60FF, 0, std::llround(b.user_speed(-300)));
  b.run(1500 * kMs);
  EXPECT_NEAR(u0(b, kU0Speed), -300, 3) << b.diag();
  EXPECT_GT(b.get(kU0Speed), 0x8000) << "U16: -300 reads as FED4h";
  EXPECT_EQ(u0(b, kU0SpeedCommand), -300);
}

// U0-02 torque command and U0-07 torque feedback in % of rated (L9023, L9028), U0-18 torque
// current in 0.01 A (L9042), on a load heavy enough that 10 % torque stays below every speed limit.
TEST(Ds5c1U0Monitors, TorqueCommandFeedbackAndCurrent) {
  EngineBench b("ds5c1", [](profile::ProductProfile&, plant::PlantDescription& d) {
    d.axes[0].load_inertia_kgm2 = 200.0 * d.axes[0].motor.rotor_inertia_kgm2;
  });
  b.set(0x6087, 0, 10000);  // 1000 %/s: 10 % within 10 ms
  ASSERT_TRUE(b.enable(mode::tq)) << b.diag();
  b.set(0x6071, 0, 100);    // 10.0 %
  b.run(200 * kMs);
  ASSERT_EQ(b.get(0x6074), 100) << b.diag();
  EXPECT_EQ(u0(b, kU0TorqueCommand), 10);
  EXPECT_NEAR(u0(b, kU0TorqueFeedback), static_cast<double>(b.get(0x6077)) / 10.0, 0.51);
  EXPECT_NEAR(u0(b, kU0TorqueFeedback), 10, 1);
  EXPECT_GT(b.feedback().current_a, 0.0);
  EXPECT_NEAR(u0(b, kU0TorqueCurrent), b.feedback().current_a * 100.0, 2.0);
}

// Which objects are monitors is the profile's word (drive.monitors), not a test of the product.
TEST(Ds5c1U0Monitors, TheProfileNamesTheMonitors) {
  EXPECT_EQ(profile::load_profile("ds5c1").drive.monitors.size(), 5u);
  EXPECT_TRUE(profile::load_profile("a6b").drive.monitors.empty());
  EXPECT_TRUE(profile::load_profile("ds1000a").drive.monitors.empty());
}

}  // namespace
}  // namespace vdrive::drive::test
