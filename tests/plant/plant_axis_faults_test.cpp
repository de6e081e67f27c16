// Machine faults of an axis (Plant::set_axis_faults): a jam holds the load where it
// seized, an obstacle stops it at the given position from the side it came (fault::end_stop), a
// load change scales a = T/J and adds a force, a failed brake does not hold. Expected values are
// computed here from the description.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant.hpp"
#include "tests/plant/plant_test_util.hpp"

namespace vdrive::plant {
namespace {

using test::rotary;
using test::run;
using test::torque;

// A vertical ball-screw axis: 20 kg on a slider along z, 10 mm lead, a 1 N m brake.
PlantDescription vertical_axis() {
  PlantDescription d;
  d.step_s = 250e-6;
  d.substeps = 4;
  d.bodies.push_back({.name = "carriage", .mass_kg = 20.0, .position_m = {0, 0, 0.5},
                      .inertia_kgm2 = {0.1, 0.1, 0.1}});
  JointSpec j;
  j.name = "z";
  j.type = JointType::slider;
  j.child = "carriage";
  j.axis = {0, 0, 1};
  j.lower_stop = -0.4;
  j.upper_stop = 0.4;
  d.joints.push_back(j);
  AxisSpec a;
  a.name = "z";
  a.joint = "z";
  a.motor = test::test_motor(1.4e-5);
  a.transmission.kind = TransmissionKind::ball_screw;
  a.transmission.lead_m = 0.01;
  a.brake = {.fitted = true, .holding_torque_nm = 1.0};
  a.encoder.counts_per_rev = 8388608;
  d.axes.push_back(a);
  return d;
}

TEST(PlantAxisFaults, JamHoldsAMultiTurnLoadWhereItSeizedAndReleases) {
  const double jl = 3e-4, jr = 1e-4, t = 0.4;
  Plant p(rotary(jl, jr));
  run(p, 0.2, torque(t));   // about 3 revolutions: the hinge's angle is far outside +-pi
  ASSERT_GT(p.feedback(0).load_position, 2 * M_PI);
  const double seized = p.feedback(0).load_position;
  p.set_axis_faults(0, {.jam = true});
  EXPECT_TRUE(p.axis_faults(0).jam);
  run(p, 1.0, torque(t));   // full torque against the jam
  EXPECT_NEAR(p.feedback(0).load_position, seized, 0.01);
  EXPECT_LT(std::abs(p.feedback(0).load_velocity), 1e-3);
  run(p, 0.5, torque(-t));  // and the other way
  EXPECT_NEAR(p.feedback(0).load_position, seized, 0.01);
  p.set_axis_faults(0, {});
  const double v0 = p.feedback(0).load_velocity;
  run(p, 0.2, torque(t));
  EXPECT_NEAR((p.feedback(0).load_velocity - v0) / 0.2, t / (jl + jr), 0.02 * t / (jl + jr)) << "free again";
}

TEST(PlantAxisFaults, JamHoldsAVerticalAxisWithoutTorqueOrBrake) {
  Plant p(vertical_axis());
  run(p, 0.01, AxisCommand{});
  const double seized = p.feedback(0).load_position;
  p.set_axis_faults(0, {.jam = true});
  run(p, 1.0, AxisCommand{});   // brake released, no torque: only the jam holds 20 kg
  EXPECT_NEAR(p.feedback(0).load_position, seized, 1e-4);
  p.set_axis_faults(0, {});
  run(p, 0.1, AxisCommand{});
  EXPECT_LT(p.feedback(0).load_velocity, -0.01) << "falls once the jam is gone";
}

TEST(PlantAxisFaults, ObstacleStopsTheLoadAtItsPositionFromEitherSide) {
  for (const double obstacle : {20.0, -5.0, 1.0}) {
    SCOPED_TRACE(obstacle);
    Plant p(rotary(3e-4));
    p.set_axis_faults(0, {.obstacle = obstacle});
    const double t = obstacle > 0 ? 0.4 : -0.4;
    run(p, 0.02, torque(t));   // 0.2 rad at 1000 rad/s^2
    EXPECT_EQ(p.feedback(0).faults & fault::end_stop, 0u) << "not there yet";
    run(p, 2.0, torque(t));
    EXPECT_NEAR(p.feedback(0).load_position, obstacle, 2e-3);
    EXPECT_LT(std::abs(p.feedback(0).load_velocity), 1e-2);
    EXPECT_NE(p.feedback(0).faults & fault::end_stop, 0u);
    run(p, 0.1, torque(-t));   // it can leave the way it came
    EXPECT_GT(std::abs(p.feedback(0).load_position - obstacle), 0.05);
    p.set_axis_faults(0, {});   // gone: the load passes the position
    run(p, 1.0, torque(t));
    EXPECT_GT(t > 0 ? p.feedback(0).load_position - obstacle : obstacle - p.feedback(0).load_position, 0.5);
  }
}

TEST(PlantAxisFaults, ObstacleOnASliderInsideItsEndStops) {
  Plant p(vertical_axis());
  p.set_axis_faults(0, {.obstacle = 0.2});
  run(p, 2.0, torque(1.0));
  EXPECT_NEAR(p.feedback(0).load_position, 0.2, 2e-3);
  EXPECT_NE(p.feedback(0).faults & fault::end_stop, 0u);
}

TEST(PlantAxisFaults, LoadScaleChangesTheAccelerationAsTorqueOverInertia) {
  const double jl = 3e-4, jr = 1e-4, t = 0.8;
  for (const double scale : {0.5, 2.0, 5.0}) {
    SCOPED_TRACE(scale);
    Plant p(rotary(jl, jr));
    p.set_axis_faults(0, {.load_scale = scale});
    run(p, 0.05, torque(t));
    const double w0 = p.feedback(0).motor_velocity_rad_s;
    run(p, 0.5, torque(t));
    const double a = (p.feedback(0).motor_velocity_rad_s - w0) / 0.5;
    const double expected = t / (scale * jl + jr);   // the rotor is not part of the load
    EXPECT_NEAR(a, expected, 0.01 * expected);
  }
}

TEST(PlantAxisFaults, LoadScaleMakesAVerticalLoadHeavier) {
  const double hold = 20.0 * 9.81 * 0.01 / (2 * M_PI);   // m g lead / 2 pi
  Plant p(vertical_axis());
  p.set_axis_faults(0, {.load_scale = 1.5});
  run(p, 0.01, torque(1.5 * hold));
  const double v0 = p.feedback(0).load_velocity;
  run(p, 0.5, torque(1.5 * hold));
  EXPECT_LT(std::abs(p.feedback(0).load_velocity - v0), 1e-6) << "1.5 m g is held by 1.5 times the torque";
  run(p, 0.2, torque(1.4 * hold));
  EXPECT_LT(p.feedback(0).load_velocity, -1e-3);
}

TEST(PlantAxisFaults, AddedForceAcceleratesTheLoad) {
  const double jl = 3e-4, jr = 1e-4, f = 0.2;
  Plant p(rotary(jl, jr));
  p.set_axis_faults(0, {.added_force = f});
  run(p, 0.5, AxisCommand{});
  EXPECT_NEAR(p.feedback(0).load_velocity / 0.5, f / (jl + jr), 0.01 * f / (jl + jr));
}

TEST(PlantAxisFaults, FrictionScaleScalesViscousAndDryFriction) {
  // Viscous b: the speed settles where the torque meets the friction, w = (T - Fc) / b. The time
  // constant J / b is 8 ms here, so 0.3 s is steady.
  const double t = 0.5, b = 0.05, coulomb = 0.1;
  for (const double scale : {1.0, 2.0, 0.0}) {
    SCOPED_TRACE(scale);
    PlantDescription d = rotary(3e-4, 1e-4);
    d.axes[0].friction.viscous = b;
    d.axes[0].friction.coulomb = coulomb;
    Plant p(d);
    p.set_axis_faults(0, {.friction_scale = scale});
    run(p, 0.3, torque(t));
    const double w = p.feedback(0).load_velocity;
    if (scale == 0.0) {
      EXPECT_NEAR(w, t / 4e-4 * 0.3, 0.02 * t / 4e-4 * 0.3) << "no friction: a = T / J all along";
    } else {
      EXPECT_NEAR(w, (t - scale * coulomb) / (scale * b), 0.02 * (t - scale * coulomb) / (scale * b));
    }
  }
}

TEST(PlantAxisFaults, FailedBrakeDoesNotHoldAGravityLoad) {
  Plant p(vertical_axis());
  AxisCommand engaged;
  engaged.brake_released = false;
  run(p, 0.5, engaged);
  EXPECT_LT(std::abs(p.feedback(0).load_position), 1e-6) << "a healthy brake holds";
  p.set_axis_faults(0, {.brake_failure = true});
  run(p, 0.1, engaged);
  EXPECT_LT(p.feedback(0).load_velocity, -0.01) << "engaged but failed: the carriage falls";
}

TEST(PlantAxisFaults, BadValuesAreRefused) {
  Plant p(rotary(3e-4));
  EXPECT_THROW(p.set_axis_faults(0, {.load_scale = 0.0}), PlantError);
  EXPECT_THROW(p.set_axis_faults(0, {.added_force = std::nan("")}), PlantError);
  EXPECT_THROW(p.set_axis_faults(0, {.obstacle = INFINITY}), PlantError);
  EXPECT_THROW(p.set_axis_faults(0, {.friction_scale = -1.0}), PlantError);
  EXPECT_THROW(p.set_axis_faults(3, {}), std::out_of_range);
  EXPECT_EQ(p.axis_faults(0).load_scale, 1.0) << "a refused change leaves the faults as they were";
}

TEST(PlantAxisFaults, SameFaultsGiveIdenticalResults) {
  auto trace = [] {
    Plant p(rotary(3e-4));
    run(p, 0.1, torque(0.5));
    p.set_axis_faults(0, {.obstacle = 12.0, .load_scale = 1.7, .added_force = -0.05});
    run(p, 1.0, torque(0.5));
    p.set_axis_faults(0, {.jam = true});
    run(p, 0.2, torque(-0.5));
    return p.feedback(0).load_position;
  };
  EXPECT_EQ(trace(), trace());
}

}  // namespace
}  // namespace vdrive::plant
