// Per-product default plants: what a drive gets with no plant file. The catalogue entries below
// are the first entries of profiles/<id>/motors.yaml (copied as inputs, not computed); the motor
// family is the product's drive.stepper.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant.hpp"
#include "plant/plant_yaml.hpp"
#include "vdrive/drive/product_plant.hpp"

namespace vdrive::drive {
namespace {

using plant::AxisCommand;
using plant::AxisSpec;
using plant::MotorKind;
using plant::MotorParams;
using plant::Plant;
using plant::PlantDescription;

enum class Family { servo, stepper };

profile::ProductProfile product(const char* id, Family family, profile::MotorSpec first) {
  profile::ProductProfile p;
  p.id = id;
  p.drive.stepper = family == Family::stepper;
  p.motors.push_back(first);
  return p;
}

profile::MotorSpec spec(const char* model, double power, double torque, double rated_rpm,
                        double max_rpm, std::uint32_t cpr) {
  profile::MotorSpec s;
  s.model = model;
  s.rated_power_w = power;
  s.rated_torque_nm = torque;
  s.rated_speed_rpm = rated_rpm;
  s.max_speed_rpm = max_rpm;
  s.encoder_counts_per_rev = cpr;
  return s;
}

TEST(DefaultPlant, A6bIsAServoWithThe23BitAbsoluteEncoder) {
  const PlantDescription d = default_plant(product("a6b", Family::servo, spec("MINAS A6 motor, 23 bit/r absolute encoder", 0, 0, 0, 0, 8388608)));
  ASSERT_EQ(d.axes.size(), 1u);
  const AxisSpec& a = d.axes[0];
  EXPECT_EQ(a.name, "a6b");
  EXPECT_EQ(a.motor.kind, MotorKind::servo);
  EXPECT_EQ(a.encoder.counts_per_rev, 8388608u);
  EXPECT_TRUE(a.encoder.absolute);
  EXPECT_GT(a.encoder.multiturn_bits, 0u);
  EXPECT_GE(a.motor.peak_torque_nm, a.motor.rated_torque_nm);
  // It runs: rated torque on rotor + equal load inertia accelerates at T / 2J (less friction).
  Plant p(d);
  AxisCommand c;
  c.torque_nm = a.motor.rated_torque_nm;
  p.command(0, c);
  for (int i = 0; i < 40; ++i) p.step();
  const double w0 = p.feedback(0).motor_velocity_rad_s;
  for (int i = 0; i < 40; ++i) p.step();
  const double acc = (p.feedback(0).motor_velocity_rad_s - w0) / 0.01;
  const double expected = (a.motor.rated_torque_nm - a.friction.coulomb) / (2 * a.motor.rotor_inertia_kgm2);
  EXPECT_NEAR(acc, expected, 0.02 * expected);
}

TEST(DefaultPlant, Ds5c1TakesRatedTorqueFromItsCatalogue) {
  const PlantDescription d =
      default_plant(product("ds5c1", Family::servo, spec("MS-220STE-TL70015B-411P0-XJ", 11000, 70, 1500, 0, 8388608)));
  EXPECT_DOUBLE_EQ(d.axes[0].motor.rated_torque_nm, 70.0);
  EXPECT_EQ(d.axes[0].motor.kind, MotorKind::servo);
  Plant p(d);
  EXPECT_EQ(p.axis_count(), 1u);
}

TEST(DefaultPlant, ServoRatedTorqueFollowsFromPowerAndSpeedWhenOnlyThoseAreKnown) {
  const MotorParams m = motor_params_from(spec("MS6S-60C30B-20P4", 400, 0, 3000, 0, 0), profile::DriveSpec{});
  EXPECT_NEAR(m.rated_torque_nm, 400 / (3000 * 2 * M_PI / 60), 1e-12);
}

TEST(DefaultPlant, Ds1000aIsAnOpenLoopCapableStepper) {
  const PlantDescription d = default_plant(product("ds1000a", Family::stepper, spec("STM28W100A", 0, 0.106, 800, 3000, 9600)));
  const AxisSpec& a = d.axes[0];
  EXPECT_EQ(a.motor.kind, MotorKind::stepper);
  EXPECT_DOUBLE_EQ(a.motor.rated_torque_nm, 0.106);
  EXPECT_NEAR(a.motor.max_speed_rad_s, 3000 * 2 * M_PI / 60, 1e-9);
  EXPECT_EQ(a.encoder.counts_per_rev, 9600u);
  EXPECT_FALSE(a.encoder.absolute);
  Plant p(d);
  AxisCommand c;
  c.stepper_open_loop = true;
  c.stepper_angle_rad = 0.01;
  p.command(0, c);
  for (int i = 0; i < 400; ++i) p.step();
  EXPECT_NEAR(p.feedback(0).motor_angle_rad, 0.01, 2e-3);
  EXPECT_EQ(p.feedback(0).lost_steps, 0);
}

TEST(DefaultPlant, EmptyCatalogueStillGivesARunnablePlant) {
  profile::ProductProfile prod;
  prod.id = "a6b";
  Plant p(default_plant(prod));
  p.step();
  EXPECT_EQ(p.axis_count(), 1u);
}

TEST(DefaultPlant, PlantFileMotorFromAProductCatalogueWithOverrides) {
  profile::MotorSpec stm42;
  stm42.model = "STM42W100A";
  stm42.rated_torque_nm = 0.3;
  stm42.max_speed_rpm = 3000;
  stm42.encoder_counts_per_rev = 16000;
  const profile::ProductProfile prod = product("ds1000a", Family::stepper, stm42);
  const plant::ProductLookup lookup = [&](std::string_view id) -> std::optional<plant::MotorCatalogue> {
    if (id == "ds1000a") return motor_catalogue(prod);
    return std::nullopt;
  };
  const PlantDescription d = plant::parse_plant_yaml(
      "plant:\n  axes:\n    - name: s\n      motor: {product: ds1000a, model: STM42W100A, rotor_inertia_kgm2: 5e-6}\n",
      "p.yaml", lookup);
  EXPECT_EQ(d.axes[0].motor.kind, MotorKind::stepper);
  EXPECT_DOUBLE_EQ(d.axes[0].motor.rated_torque_nm, 0.3);
  EXPECT_DOUBLE_EQ(d.axes[0].motor.rotor_inertia_kgm2, 5e-6);
}

}  // namespace
}  // namespace vdrive::drive
