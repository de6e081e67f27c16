// Two drives in one world on stacked sliders (an X-Y gantry): X carries the Y carriage, so X's
// drive moves both masses while Y's moves only its own.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant.hpp"
#include "tests/plant/plant_test_util.hpp"

namespace vdrive::plant {
namespace {

PlantDescription gantry() {
  PlantDescription d;
  d.step_s = 250e-6;
  d.substeps = 2;
  d.gravity = {0, 0, -9.81};
  d.bodies.push_back({.name = "bridge", .mass_kg = 12.0, .position_m = {0, 0, 0}, .inertia_kgm2 = {1, 1, 1}});
  d.bodies.push_back({.name = "head", .mass_kg = 3.0, .position_m = {0, 0, 0.1}, .inertia_kgm2 = {0.1, 0.1, 0.1}});
  JointSpec x, y;
  x.name = "x";
  x.type = JointType::slider;
  x.child = "bridge";
  x.axis = {1, 0, 0};
  y.name = "y";
  y.type = JointType::slider;
  y.parent = "bridge";
  y.child = "head";
  y.axis = {0, 1, 0};
  d.joints = {x, y};
  for (const char* name : {"x", "y"}) {
    AxisSpec a;
    a.name = name;
    a.joint = name;
    a.motor = test::test_motor(3e-5);
    a.transmission = {.kind = TransmissionKind::ball_screw, .ratio = 1.0, .lead_m = 0.02};
    d.axes.push_back(a);
  }
  return d;
}

TEST(Gantry, EachDriveMovesTheMassItCarries) {
  Plant p(gantry());
  const double r = 0.02 / (2 * M_PI), reflected = 3e-5 / (r * r), t = 0.3;
  AxisCommand c;
  c.torque_nm = t;
  p.command(0, c);
  p.command(1, c);
  for (int i = 0; i < 40; ++i) p.step();
  const double vx0 = p.feedback(0).load_velocity, vy0 = p.feedback(1).load_velocity;
  for (int i = 0; i < 800; ++i) p.step();  // 0.2 s
  const double ax = (p.feedback(0).load_velocity - vx0) / 0.2;
  const double ay = (p.feedback(1).load_velocity - vy0) / 0.2;
  // The plant lumps a rigid linear axis's reflected rotor mass into the body it moves
  // (docs/plant.md, simplifications), so X also carries Y's reflected mass.
  const double ax_expected = (t / r) / (12.0 + 3.0 + 2 * reflected);
  const double ay_expected = (t / r) / (3.0 + reflected);
  EXPECT_NEAR(ax, ax_expected, 0.01 * ax_expected);
  EXPECT_NEAR(ay, ay_expected, 0.01 * ay_expected);
}

}  // namespace
}  // namespace vdrive::plant
