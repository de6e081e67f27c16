// The power stage around the motor, on the whole drive: the holding brake (A6B sequenced by the
// drive, DS1000A-EC set by the master through 60FEh) and the torque-off inputs (A6B STO, DS1000A-EC
// TO), checked on the plant.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/drive/engine_bench.hpp"

namespace vdrive::drive::test {
namespace {

// A brake of `holding` N m on the motor shaft.
EngineBench::Tweak brake(double holding) {
  return [holding](profile::ProductProfile&, plant::PlantDescription& d) {
    d.axes[0].brake.fitted = true;
    d.axes[0].brake.holding_torque_nm = holding;
  };
}

// A6B: the drive releases the brake when the power stage comes on and engages it when it goes off
// (3510h sequence, brake rule "automatic", L27945-L28090): a load torque below the holding torque
// turns the motor only while the drive is enabled and holding it does not matter.
TEST(EnginePowerStage, A6bBrakeHoldsTheLoadWhileDisabled) {
  {
    EngineBench free_axis("a6b");
    free_axis.plant().set_external_load(0, 0.3);
    free_axis.run(300 * kMs);
    ASSERT_GT(std::abs(free_axis.motor_rpm()), 10.0) << "without a brake the load turns the motor";
  }
  EngineBench b("a6b", brake(2.0));
  b.plant().set_external_load(0, 0.3);  // N m on the load
  b.run(300 * kMs);
  EXPECT_NEAR(b.motor_rpm(), 0.0, 0.5) << "disabled: the brake holds 0.3 N m";
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.set(0x6083, 0, std::llround(20 * b.per_rev()));
  b.set(0x60FF, 0, std::llround(b.user_speed(60)));
  b.run(500 * kMs);
  EXPECT_NEAR(b.motor_rpm(), 60.0, 3.0) << "enabled: the brake is released and the drive turns " << b.diag();
}

// DS1000A-EC: the brake follows 60FEh-01h bit 0 "set brake" only under the 60FEh-02h mask; it is
// engaged at power-on and stays so until the master unmasks it (L3505-L3525).
TEST(EnginePowerStage, Ds1000aBrakeIsTheMastersOutput) {
  EngineBench b("ds1000a", brake(5.0));
  b.set(0x6083, 0, std::llround(20 * b.per_rev()));
  ASSERT_TRUE(b.enable(mode::pv)) << b.diag();
  b.set(0x60FF, 0, std::llround(b.user_speed(60)));
  b.run(300 * kMs);
  EXPECT_NEAR(b.motor_rpm(), 0.0, 1.0) << "brake still engaged: the motor cannot turn";
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled);
  b.set(0x60FE, 1, 0);  // set brake = 0 ...
  b.set(0x60FE, 2, 1);  // ... and unmask bit 0
  b.run(500 * kMs);
  EXPECT_NEAR(b.motor_rpm(), 60.0, 3.0) << "brake released by the master " << b.diag();
}

// Torque off (A6B STO, L9436-L9438; DS1000A-EC TO input, L5566-L5572): the power stage drops to
// Switch on disabled without an alarm, the drive cannot be enabled while it lasts, and enables
// again once it is gone.
TEST(EnginePowerStage, TorqueOffInputForcesSwitchOnDisabled) {
  for (const char* id : {"a6b", "ds1000a"}) {
    SCOPED_TRACE(id);
    EngineBench b(id);
    ASSERT_TRUE(b.profile().drive.torque_off_input);
    ASSERT_TRUE(b.enable(mode::csp)) << b.diag();
    b.engine().set_torque_off_input(true);
    b.run(200 * kMs);
    EXPECT_EQ(b.engine().state(), PdsState::SwitchOnDisabled) << b.diag();
    EXPECT_EQ(b.get(0x603F), 0) << "no alarm";
    EXPECT_FALSE(b.enable(mode::csp)) << "no enable while torque is off";
    b.engine().set_torque_off_input(false);
    b.command(0, 5 * kMs);
    EXPECT_TRUE(b.enable(mode::csp)) << b.diag();
  }
}

// DS5C1: no torque-off input (P5-68 is an alarm input, L5321): the setting has no effect.
TEST(EnginePowerStage, Ds5c1HasNoTorqueOffInput) {
  EngineBench b("ds5c1");
  ASSERT_FALSE(b.profile().drive.torque_off_input);
  ASSERT_TRUE(b.enable(mode::csp)) << b.diag();
  b.engine().set_torque_off_input(true);
  b.run(50 * kMs);
  EXPECT_EQ(b.engine().state(), PdsState::OperationEnabled);
}

}  // namespace
}  // namespace vdrive::drive::test
