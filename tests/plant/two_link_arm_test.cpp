// Two drives on one shared two-link arm (scenarios/plants/two_link_arm.yaml): the measured joint
// accelerations must match the textbook dynamics M(q) q'' + C(q, q') q' + G(q) = tau, with the
// motors' reflected rotor inertia lumped into each link (I_i + J_rotor,i N_i^2) and tau_i = N_i T_i.
#include <gtest/gtest.h>

#include <cmath>

#include "plant/plant.hpp"
#include "plant/plant_yaml.hpp"

namespace vdrive::plant {
namespace {

const std::string kArm = std::string(VDRIVE_SOURCE_DIR) + "/scenarios/plants/two_link_arm.yaml";

struct Arm {  // the analytic model, parameters read from the same description
  double m1, m2, l1, lc1, lc2, i1, i2, n1, n2, g;
  explicit Arm(const PlantDescription& d) {
    const BodySpec& b1 = d.bodies[0];
    const BodySpec& b2 = d.bodies[1];
    m1 = b1.mass_kg;
    m2 = b2.mass_kg;
    l1 = d.joints[1].anchor_m[0] - d.joints[0].anchor_m[0];
    lc1 = b1.position_m[0] - d.joints[0].anchor_m[0];
    lc2 = b2.position_m[0] - d.joints[1].anchor_m[0];
    n1 = d.axes[0].transmission.ratio;
    n2 = d.axes[1].transmission.ratio;
    i1 = b1.inertia_kgm2[1] + d.axes[0].motor.rotor_inertia_kgm2 * n1 * n1;
    i2 = b2.inertia_kgm2[1] + d.axes[1].motor.rotor_inertia_kgm2 * n2 * n2;
    g = -d.gravity[2];
  }
  // q'' for joint torques tau at state (q, qd).
  void accel(const double q[2], const double qd[2], const double tau[2], double out[2]) const {
    const double c2 = std::cos(q[1]), s2 = std::sin(q[1]);
    const double m11 = m1 * lc1 * lc1 + i1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * c2) + i2;
    const double m12 = m2 * (lc2 * lc2 + l1 * lc2 * c2) + i2;
    const double m22 = m2 * lc2 * lc2 + i2;
    const double h = m2 * l1 * lc2 * s2;
    const double cq1 = -h * (2 * qd[0] * qd[1] + qd[1] * qd[1]);
    const double cq2 = h * qd[0] * qd[0];
    const double g1 = (m1 * lc1 + m2 * l1) * g * std::cos(q[0]) + m2 * lc2 * g * std::cos(q[0] + q[1]);
    const double g2 = m2 * lc2 * g * std::cos(q[0] + q[1]);
    const double r1 = tau[0] - cq1 - g1, r2 = tau[1] - cq2 - g2;
    const double det = m11 * m22 - m12 * m12;
    out[0] = (m22 * r1 - m12 * r2) / det;
    out[1] = (-m12 * r1 + m11 * r2) / det;
  }
  void gravity(const double q[2], double out[2]) const {
    out[0] = (m1 * lc1 + m2 * l1) * g * std::cos(q[0]) + m2 * lc2 * g * std::cos(q[0] + q[1]);
    out[1] = m2 * lc2 * g * std::cos(q[0] + q[1]);
  }
};

struct State {
  double q[2], qd[2];
};
State state(const Plant& p) {
  return {{p.feedback(0).load_position, p.feedback(1).load_position},
          {p.feedback(0).load_velocity, p.feedback(1).load_velocity}};
}

void command(Plant& p, double t1, double t2) {
  AxisCommand c;
  c.torque_nm = t1;
  p.command(0, c);
  c.torque_nm = t2;
  p.command(1, c);
}

TEST(TwoLinkArm, LoadsFromTheScenarioFile) {
  const PlantDescription d = load_plant_file(kArm);
  ASSERT_EQ(d.axes.size(), 2u);
  Plant p(d);
  EXPECT_EQ(p.axis_index("elbow"), 1u);
  EXPECT_NEAR(p.feedback(0).load_position, 0.3, 1e-9);
  EXPECT_NEAR(p.feedback(1).load_position, 0.5, 1e-9);
  // The encoder sits on the motor: 50 motor turns per shoulder turn.
  EXPECT_NEAR(p.feedback(0).motor_angle_rad, 50 * 0.3, 1e-9);
}

TEST(TwoLinkArm, MotorTorquesEqualToTheGravityTermsHoldTheArm) {
  const PlantDescription d = load_plant_file(kArm);
  const Arm arm(d);
  Plant p(d);
  double g[2];
  arm.gravity(state(p).q, g);
  command(p, g[0] / arm.n1, g[1] / arm.n2);
  for (int i = 0; i < 40; ++i) p.step();  // 10 ms: the current loops have settled
  // The pose is an unstable balance (a raised arm), so check the acceleration, not the drift:
  // with the gravity torques applied it must vanish, compared with the free fall acceleration.
  const double h = p.step_s();
  const State before = state(p);
  p.step();
  p.step();
  const State after = state(p);
  double fall[2];
  const double none[2] = {0, 0};
  arm.accel(before.q, none, none, fall);
  for (int k = 0; k < 2; ++k) {
    const double a = (after.qd[k] - before.qd[k]) / (2 * h);
    EXPECT_LT(std::abs(a), 0.01 * std::abs(fall[k])) << "joint " << k;
  }
  EXPECT_NEAR(state(p).q[0], 0.3, 1e-3);
  EXPECT_NEAR(state(p).q[1], 0.5, 1e-3);
}

// Central difference of the joint velocities around the current state, against the model.
// The model gets the motors' actual torque (after the current loop and speed limit).
void expect_dynamics(Plant& p, const Arm& arm, double tolerance) {
  const double h = p.step_s();
  const State before = state(p);
  p.step();
  const State mid = state(p);
  p.step();
  const State after = state(p);
  const double tau[2] = {arm.n1 * p.feedback(0).torque_nm, arm.n2 * p.feedback(1).torque_nm};
  double model[2];
  arm.accel(mid.q, mid.qd, tau, model);
  for (int k = 0; k < 2; ++k) {
    const double measured = (after.qd[k] - before.qd[k]) / (2 * h);
    EXPECT_NEAR(measured, model[k], tolerance * std::max(1.0, std::abs(model[k])))
        << "joint " << k << " q=" << mid.q[0] << "," << mid.q[1] << " qd=" << mid.qd[0] << "," << mid.qd[1];
  }
}

TEST(TwoLinkArm, ShoulderTorqueAloneAcceleratesTheElbowThroughTheMassMatrix) {
  const PlantDescription d = load_plant_file(kArm);
  const Arm arm(d);
  Plant p(d);
  double g[2];
  arm.gravity(state(p).q, g);
  // Gravity compensated, plus 0.3 N m extra on the shoulder motor only.
  command(p, g[0] / arm.n1 + 0.3, g[1] / arm.n2);
  for (int i = 0; i < 40; ++i) p.step();  // let the current loops settle (10 ms)
  const State s = state(p);
  double a[2];
  const double tau[2] = {g[0] + arm.n1 * 0.3, g[1]};
  arm.accel(s.q, s.qd, tau, a);
  EXPECT_GT(a[0], 0.0);
  EXPECT_LT(a[1], 0.0);  // the coupling: the elbow swings back when the shoulder accelerates
  expect_dynamics(p, arm, 0.01);
  EXPECT_LT(p.feedback(1).load_velocity, 0.0);
}

TEST(TwoLinkArm, MovingArmFollowsMassMatrixCoriolisAndGravity) {
  const PlantDescription d = load_plant_file(kArm);
  const Arm arm(d);
  Plant p(d);
  // Let the arm swing down under gravity with both drives pushing a little, and check the dynamics
  // at several points while it moves (Coriolis and centrifugal terms large).
  const double t1 = 0.2, t2 = 0.05;
  command(p, t1, t2);
  for (int round = 0; round < 5; ++round) {
    for (int i = 0; i < 400; ++i) p.step();  // 100 ms
    const State s = state(p);
    EXPECT_GT(std::abs(s.qd[0]) + std::abs(s.qd[1]), 0.5) << "round " << round;
    expect_dynamics(p, arm, 0.01);
  }
}

TEST(TwoLinkArm, EnergyIsConservedWhileSwingingFreely) {
  PlantDescription d = load_plant_file(kArm);
  d.joints[0].initial = 1.2;  // let it fall from high up
  d.joints[1].initial = -0.8;
  Plant p(d);
  const Arm arm(d);
  const double scale = (arm.m1 * arm.lc1 + arm.m2 * (arm.l1 + arm.lc2)) * arm.g;  // 1 m of drop
  const double e0 = p.energy();
  double worst = 0;
  for (int i = 0; i < 40000; ++i) {  // 10 s
    p.step();
    worst = std::max(worst, std::abs(p.energy() - e0));
  }
  EXPECT_LT(worst, 0.01 * scale);
}

}  // namespace
}  // namespace vdrive::plant
