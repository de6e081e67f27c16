// Plant YAML: a good file loads, every kind of bad input is refused with file, line and field.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant.hpp"
#include "plant/plant_yaml.hpp"

namespace vdrive::plant {
namespace {

std::string error_of(const std::string& yaml, const ProductLookup& products = {}) {
  try {
    parse_plant_yaml(yaml, "p.yaml", products);
  } catch (const PlantYamlError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kAxis = "plant:\n  axes:\n    - name: x\n";

TEST(PlantYaml, MinimalFileGivesOneAxisWithDefaults) {
  const PlantDescription d = parse_plant_yaml(kAxis, "p.yaml");
  ASSERT_EQ(d.axes.size(), 1u);
  EXPECT_EQ(d.axes[0].name, "x");
  EXPECT_EQ(d.axes[0].transmission.kind, TransmissionKind::direct);
  Plant p(d);
  EXPECT_EQ(p.axis_count(), 1u);
}

TEST(PlantYaml, ReadsEveryAxisSection) {
  const PlantDescription d = parse_plant_yaml(R"(plant:
  step_s: 0.0005
  substeps: 3
  bodies: [{name: c, mass_kg: 5, position_m: [0, 0, 1]}]
  joints: [{name: z, type: slider, child: c, axis: [0, 0, 1], lower_stop: -0.2, upper_stop: 0.3}]
  axes:
    - name: z
      joint: z
      motor: {kind: servo, rated_torque_nm: 1.3, peak_torque_nm: 3.8, max_speed_rpm: 3000}
      transmission: {type: ball_screw, lead_m: 0.005, ratio: 2, efficiency: 0.9, backlash: 1e-5, stiffness: 1e7, damping: 100}
      friction: {coulomb: 5, breakaway: 8, stribeck_velocity: 0.002, viscous: 30}
      encoder: {counts_per_rev: 131072, absolute: false, multiturn_bits: 0, index_angle_rad: 1.0}
      brake: {holding_torque_nm: 2.5}
      switches: {negative_limit: -0.15, positive_limit: 0.25, home: [0, 0.01], probe1: [0.1, 0.1001]}
      load_profile: [[0, 0], [1, -20], [2, -20]]
)", "p.yaml");
  EXPECT_DOUBLE_EQ(d.step_s, 0.0005);
  EXPECT_EQ(d.substeps, 3);
  const AxisSpec& a = d.axes[0];
  EXPECT_NEAR(a.motor.max_speed_rad_s, 3000 * 2 * M_PI / 60, 1e-9);
  EXPECT_EQ(a.transmission.kind, TransmissionKind::ball_screw);
  EXPECT_DOUBLE_EQ(a.transmission.stiffness, 1e7);
  EXPECT_DOUBLE_EQ(a.friction.breakaway, 8);
  EXPECT_EQ(a.encoder.counts_per_rev, 131072u);
  EXPECT_FALSE(a.encoder.absolute);
  EXPECT_TRUE(a.brake.fitted);
  ASSERT_TRUE(a.switches.home.has_value());
  EXPECT_DOUBLE_EQ(a.switches.home->to, 0.01);
  ASSERT_EQ(a.load_profile.size(), 3u);
  EXPECT_DOUBLE_EQ(a.load_profile[1].second, -20);
  EXPECT_EQ(d.joints[0].type, JointType::slider);
}

TEST(PlantYaml, ErrorsNameFileLineAndField) {
  EXPECT_EQ(error_of("plant:\n  axes:\n    - name: x\n      transmission: {type: gearbox, ratio: 0}\n"),
            "p.yaml:4:44: plant.axes[0].transmission.ratio: must be > 0");
  EXPECT_EQ(error_of("plant:\n  axes:\n    - name: x\n      colour: red\n"),
            "p.yaml:4:7: plant.axes[0].colour: unknown field");
  EXPECT_EQ(error_of("plant:\n  axes:\n    - name: x\n      joint: nowhere\n"),
            "p.yaml:4:14: plant.axes[0].joint: no joint named 'nowhere'");
  EXPECT_EQ(error_of("plant:\n  step_s: fast\n  axes:\n    - name: x\n"),
            "p.yaml:2:11: plant.step_s: must be a number, got 'fast'");
  EXPECT_EQ(error_of("plant:\n  axes:\n    - name: x\n      transmission: {type: chain}\n"),
            "p.yaml:4:28: plant.axes[0].transmission.type: must be direct, gearbox, belt or ball_screw");
  EXPECT_EQ(error_of("plant:\n  joints: [{name: j, child: ghost}]\n  axes: [{name: x}]\n"),
            "p.yaml:2:29: plant.joints[0].child: no body named 'ghost'");
  EXPECT_EQ(error_of("plant:\n  axes: []\n"), "p.yaml:2:9: plant.axes: at least one axis is needed");
  EXPECT_EQ(error_of("plant:\n  axes:\n    - name: x\n      motor: {product: a6b}\n"),
            "p.yaml:4:24: plant.axes[0].motor.product: unknown product 'a6b'");
  EXPECT_EQ(error_of("plant:\n  gravity: [0, 0]\n  axes: [{name: x}]\n"),
            "p.yaml:2:12: plant.gravity: must be a list of 3 numbers");
  EXPECT_EQ(error_of("plant:\n  bodies: {name: b}\n  axes: [{name: x}]\n"),
            "p.yaml:2:11: plant.bodies: must be a list");
  EXPECT_EQ(error_of("plant: [\n"), "p.yaml:2:1: end of sequence flow not found");
  EXPECT_EQ(error_of("plant:\n  axes:\n    - name: x\n      transmission: {backlash: 0.01}\n"),
            "p.yaml:4:21: plant.axes[0].transmission.stiffness: must be > 0 when backlash is set");
}

// Found by fuzz_config: a document that is a scalar or a list escaped as yaml-cpp's BadSubscript,
// and an empty one was refused without a line.
TEST(PlantYaml, ADocumentThatIsNoMappingIsAnError) {
  for (const char* yaml : {"42\n", "- plant\n", "plant\n", "# nothing but a comment\n", ""}) {
    const std::string error = error_of(yaml);
    EXPECT_EQ(error.rfind("p.yaml:1:", 0), 0u) << error;
    EXPECT_NE(error.find("plant: missing (top-level key 'plant:'"), std::string::npos) << error;
  }
}

TEST(PlantYaml, MissingFileIsAnError) {
  EXPECT_THROW(load_plant_file("/nonexistent/plant.yaml"), PlantYamlError);
}

TEST(PlantYaml, MotorFromAProductCatalogueWithOverrides) {
  MotorCatalogue catalogue;
  MotorParams stm42;
  stm42.model = "STM42W100A";
  stm42.kind = MotorKind::stepper;
  stm42.rated_torque_nm = 0.3;
  stm42.max_speed_rad_s = 3000 * 2 * M_PI / 60;
  catalogue.default_motor = stm42;
  catalogue.motors.push_back(stm42);
  const ProductLookup lookup = [&](std::string_view id) -> std::optional<MotorCatalogue> {
    if (id == "ds1000a") return catalogue;
    return std::nullopt;
  };
  const PlantDescription d = parse_plant_yaml(
      "plant:\n  axes:\n    - name: s\n      motor: {product: ds1000a, model: STM42W100A, rotor_inertia_kgm2: 5e-6}\n",
      "p.yaml", lookup);
  EXPECT_EQ(d.axes[0].motor.kind, MotorKind::stepper);
  EXPECT_DOUBLE_EQ(d.axes[0].motor.rated_torque_nm, 0.3);
  EXPECT_DOUBLE_EQ(d.axes[0].motor.rotor_inertia_kgm2, 5e-6);
  EXPECT_EQ(error_of("plant:\n  axes:\n    - name: s\n      motor: {product: ds1000a, model: STM99}\n", lookup),
            "p.yaml:4:40: plant.axes[0].motor.model: no motor 'STM99' in ds1000a's catalogue");
}

TEST(PlantDescriptionChecks, PlantRefusesInconsistentDescriptions) {
  PlantDescription d = parse_plant_yaml(kAxis, "p.yaml");
  d.axes[0].transmission.kind = TransmissionKind::ball_screw;
  d.axes[0].transmission.lead_m = 0.01;
  try {
    Plant p(d);
    FAIL() << "built a ball screw on a hinge";
  } catch (const PlantError& e) {
    EXPECT_STREQ(e.what(), "axis 'x': transmission does not fit joint 'x.joint' (ball screw/linear belt need a slider)");
  }
  d = parse_plant_yaml(kAxis, "p.yaml");
  d.axes[0].transmission.stiffness = 1e9;  // resonance far above what the step can integrate
  EXPECT_THROW(Plant{d}, PlantError);
}

}  // namespace
}  // namespace vdrive::plant
