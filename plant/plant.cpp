#include "plant/plant.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "common/cached_exp.hpp"
#include "plant/friction.hpp"
#include "plant/load_profile.hpp"
#include "plant/lone_hinge_step.hpp"
#include "plant/motor_torque.hpp"
#include "plant/thermal_network.hpp"

namespace vdrive::plant {

namespace {

// ODE wants its per-thread data in every thread that steps a world (allocated once per thread).
void ensure_ode_thread_data() {
  thread_local bool allocated = false;
  if (!allocated) allocated = dAllocateODEDataForThread(dAllocateMaskAll) != 0;
}

void ensure_ode() {
  static std::once_flag once;
  std::call_once(once, [] { dInitODE2(0); });
  ensure_ode_thread_data();
}

double wrap_pi(double a) { return std::remainder(a, 2.0 * M_PI); }

bool is_linear(const TransmissionSpec& t, JointType joint) {
  return t.kind == TransmissionKind::ball_screw ||
         (t.kind == TransmissionKind::belt && joint == JointType::slider);
}

// Load units per motor radian.
double load_per_motor_rad(const TransmissionSpec& t, JointType joint) {
  switch (t.kind) {
    case TransmissionKind::direct: return 1.0;
    case TransmissionKind::gearbox: return 1.0 / t.ratio;
    case TransmissionKind::belt:
      return joint == JointType::slider ? 0.5 * t.pulley_diameter_m / t.ratio : 1.0 / t.ratio;
    case TransmissionKind::ball_screw: return t.lead_m / (2.0 * M_PI) / t.ratio;
  }
  return 1.0;
}

[[noreturn]] void fail(const std::string& what) { throw PlantError(what); }

// n.I n for a unit vector n in the mass's (body) frame; `residual` = |I n - (n.I n) n|, which is
// zero when n is a principal axis.
double axial_inertia(const dMass& m, const double (&n)[3], double* residual = nullptr) {
  double in[3], jn = 0;
  for (int i = 0; i < 3; ++i) {
    in[i] = m.I[i * 4 + 0] * n[0] + m.I[i * 4 + 1] * n[1] + m.I[i * 4 + 2] * n[2];
    jn += n[i] * in[i];
  }
  if (residual) *residual = std::hypot(in[0] - jn * n[0], in[1] - jn * n[1], in[2] - jn * n[2]);
  return jn;
}

// What a joint moves of `m`: its mass on a slider, its inertia about the hinge axis as specified
// (the zero configuration, where the body's frame is the world's).
double load_along(const dMass& m, const JointSpec& js) {
  if (js.type != JointType::hinge) return m.mass;
  const double len = std::hypot(js.axis[0], js.axis[1], js.axis[2]);
  const double n[3] = {js.axis[0] / len, js.axis[1] / len, js.axis[2] / len};
  return axial_inertia(m, n);
}

// Inertia of a joint's body about its hinge axis now (see axial_inertia for `residual`). The axis
// is taken in the body frame, where turning about it does not move it.
double inertia_about_hinge(dJointID hinge, dBodyID body, double* residual = nullptr) {
  dVector3 axis;
  dJointGetHingeAxis(hinge, axis);
  const dReal* r = dBodyGetRotation(body);
  double n[3];
  for (int i = 0; i < 3; ++i) n[i] = r[0 * 4 + i] * axis[0] + r[1 * 4 + i] * axis[1] + r[2 * 4 + i] * axis[2];
  dMass m;
  dBodyGetMass(body, &m);
  return axial_inertia(m, n, residual);
}

}  // namespace

struct Plant::Impl {
  struct Body {
    std::string name;
    dBodyID id = nullptr;
    double own_mass = 0;          // without reflected rotor mass (gravity acts on this)
    bool manual_gravity = false;  // reflected mass added: gravity applied by hand on own_mass
    double base_mass = 0;         // own_mass before an AxisFaults::load_scale
  };
  struct Joint {
    JointSpec spec;
    dJointID id = nullptr;
    int parent = -1, child = -1;  // body indices, -1 = world
    double pos = 0, vel = 0;      // continuous position (hinge angle unwrapped)
    double prev_raw = 0;
    bool fault_stops = false;     // jam/obstacle stops are set (hinge: its angle frame moved)
    // Closed form (lone_hinge_step.hpp): lone_inertia > 0 where it applies; while `closed`, the
    // ODE body is disabled and stale by pos - ode_pos about the hinge axis.
    double lone_inertia = 0;
    bool closed = false;
    double ode_pos = 0;
  };
  struct Axis {
    AxisSpec spec;
    int joint = -1;
    double r = 1.0;               // load units per motor rad
    bool two_mass = false;
    dBodyID rotor = nullptr;
    dJointID rotor_hinge = nullptr;
    double rotor_prev_raw = 0, rotor_angle = 0, rotor_vel = 0;
    double current = 0, torque = 0, loss_j = 0;
    CachedExp current_lag;
    ThermalNetwork thermal;
    Encoder encoder;
    AxisCommand cmd;
    double ext_load = 0;
    std::uint32_t ext_inputs = 0;
    std::uint32_t sensor_inputs = 0;  // the switches as of the last step
    std::optional<bool> brake_control;  // released, when something other than the drive drives the coil
    AxisFeedback fb;
    AxisFaults faults;
    double lock_at = 0;           // jam: the load position held
    bool obstacle_above = true;   // obstacle: a stop above the load (else below)
    dMass load_own{}, load_full{};  // the load body's mass without / with the reflected rotor

    Axis(const AxisSpec& s, double step, double angle0)
        : spec(s), thermal(s.motor, step), encoder(s.encoder, angle0) {}
    double motor_angle(const Joint& j) const { return two_mass ? rotor_angle : j.pos / r; }
    double motor_vel(const Joint& j) const { return two_mass ? rotor_vel : j.vel / r; }
    double twist(const Joint& j) const {  // dead-zone-filtered coupling deflection, load units
      const double d = r * rotor_angle - j.pos, half = 0.5 * spec.transmission.backlash;
      return d > half ? d - half : d < -half ? d + half : 0.0;
    }
  };

  PlantDescription desc;
  dWorldID world = nullptr;
  std::vector<Body> bodies;
  std::vector<Joint> joints;
  std::vector<Axis> axes;
  double dt = 0;
  int ode_bodies_enabled = 0;   // dWorldStep is skipped when every body is stepped in closed form
  std::int64_t steps = 0;
  Nanos step_ns = 0;

  ~Impl() {
    if (world) dWorldDestroy(world);  // destroys bodies and joints too
  }

  int body_index(const std::string& name) const {
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].name == name) return static_cast<int>(i);
    return -1;
  }

  void read_joint(Joint& j) {
    if (j.spec.type == JointType::hinge) {
      const double raw = dJointGetHingeAngle(j.id);
      j.pos += wrap_pi(raw - j.prev_raw);
      j.prev_raw = raw;
      j.vel = dJointGetHingeAngleRate(j.id);
    } else {
      j.pos = dJointGetSliderPosition(j.id);
      j.vel = dJointGetSliderPositionRate(j.id);
    }
  }
  void read_rotor(Axis& a) {
    const double raw = dJointGetHingeAngle(a.rotor_hinge);
    a.rotor_angle += wrap_pi(raw - a.rotor_prev_raw);
    a.rotor_prev_raw = raw;
    a.rotor_vel = dJointGetHingeAngleRate(a.rotor_hinge);
  }

  void build();
  void add_axis_load_body(AxisSpec& a, std::size_t index);
  void create_joint(Joint& j);
  void place_initial(const Joint& j);
  void find_lone_hinges();
  void set_closed(Joint& j, bool closed);
  void substep(double t);
  void finish_step();
  void set_stops(const Joint& j, double lo, double hi);
  void apply_fault_stops(Axis& a);
  void scale_load(Axis& a, double scale);
};

void Plant::Impl::add_axis_load_body(AxisSpec& a, std::size_t index) {
  // An axis with no machine joint drives its own inertia on a hinge about z, centred on the axis.
  BodySpec b;
  b.name = a.name + ".load";
  b.mass_kg = 1.0;
  b.position_m = {static_cast<double>(index), -10.0, 0.0};
  const double j = a.load_inertia_kgm2 > 0 ? a.load_inertia_kgm2 : a.motor.rotor_inertia_kgm2;
  b.inertia_kgm2 = {j, j, j};
  desc.bodies.push_back(b);
  JointSpec js;
  js.name = a.name + ".joint";
  js.child = b.name;
  js.anchor_m = b.position_m;
  js.axis = {0, 0, 1};
  desc.joints.push_back(js);
  a.joint = js.name;
}

void Plant::Impl::create_joint(Joint& j) {
  const JointSpec& s = j.spec;
  dBodyID child = bodies[j.child].id;
  dBodyID parent = j.parent >= 0 ? bodies[j.parent].id : nullptr;
  if (s.type == JointType::hinge) {
    j.id = dJointCreateHinge(world, nullptr);
    dJointAttach(j.id, child, parent);
    dJointSetHingeAnchor(j.id, s.anchor_m[0], s.anchor_m[1], s.anchor_m[2]);
    dJointSetHingeAxis(j.id, s.axis[0], s.axis[1], s.axis[2]);
    if (s.lower_stop) dJointSetHingeParam(j.id, dParamLoStop, *s.lower_stop);
    if (s.upper_stop) dJointSetHingeParam(j.id, dParamHiStop, *s.upper_stop);
    dJointSetHingeParam(j.id, dParamBounce, s.stop_bounce);
    dJointSetHingeParam(j.id, dParamVel, 0.0);
    dJointSetHingeParam(j.id, dParamFMax, 0.0);
  } else {
    j.id = dJointCreateSlider(world, nullptr);
    dJointAttach(j.id, child, parent);
    dJointSetSliderAxis(j.id, s.axis[0], s.axis[1], s.axis[2]);
    if (s.lower_stop) dJointSetSliderParam(j.id, dParamLoStop, *s.lower_stop);
    if (s.upper_stop) dJointSetSliderParam(j.id, dParamHiStop, *s.upper_stop);
    dJointSetSliderParam(j.id, dParamBounce, s.stop_bounce);
    dJointSetSliderParam(j.id, dParamVel, 0.0);
    dJointSetSliderParam(j.id, dParamFMax, 0.0);
  }
}

// Move the joint's child and everything hanging from it to the joint's initial position.
void Plant::Impl::place_initial(const Joint& j) {
  if (j.spec.initial == 0.0) return;
  std::vector<bool> moved(bodies.size(), false);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (int cur = static_cast<int>(b); cur >= 0;) {
      if (cur == j.child) { moved[b] = true; break; }
      int parent = -2;
      for (const Joint& k : joints)
        if (k.child == cur) parent = k.parent;
      cur = parent == -2 ? -1 : parent;
    }
  }
  dVector3 axis, anchor{0, 0, 0, 0};
  dMatrix3 rot;
  if (j.spec.type == JointType::hinge) {
    dJointGetHingeAxis(j.id, axis);
    dJointGetHingeAnchor(j.id, anchor);
    dRFromAxisAndAngle(rot, axis[0], axis[1], axis[2], j.spec.initial);
  } else {
    dJointGetSliderAxis(j.id, axis);
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!moved[b]) continue;
    dBodyID id = bodies[b].id;
    const dReal* p = dBodyGetPosition(id);
    if (j.spec.type == JointType::slider) {
      dBodySetPosition(id, p[0] + axis[0] * j.spec.initial, p[1] + axis[1] * j.spec.initial,
                       p[2] + axis[2] * j.spec.initial);
      continue;
    }
    dVector3 rel{p[0] - anchor[0], p[1] - anchor[1], p[2] - anchor[2], 0}, out;
    dMultiply0_331(out, rot, rel);
    dBodySetPosition(id, anchor[0] + out[0], anchor[1] + out[1], anchor[2] + out[2]);
    dMatrix3 r2;
    dMultiply0_333(r2, rot, dBodyGetRotation(id));
    dBodySetRotation(id, r2);
  }
}

void Plant::Impl::build() {
  if (!(desc.step_s > 0)) fail("plant: step_s must be > 0");
  if (desc.substeps < 1) fail("plant: substeps must be >= 1");
  if (desc.axes.empty()) fail("plant: at least one axis is needed");
  dt = desc.step_s / desc.substeps;
  step_ns = static_cast<Nanos>(std::llround(desc.step_s * 1e9));
  for (std::size_t i = 0; i < desc.axes.size(); ++i)
    if (desc.axes[i].joint.empty()) add_axis_load_body(desc.axes[i], i);

  world = dWorldCreate();
  dWorldSetGravity(world, desc.gravity[0], desc.gravity[1], desc.gravity[2]);
  dWorldSetERP(world, 0.2);
  dWorldSetCFM(world, 1e-10);

  for (const BodySpec& s : desc.bodies) {
    if (body_index(s.name) >= 0) fail("body '" + s.name + "': duplicate name");
    if (!(s.mass_kg > 0)) fail("body '" + s.name + "': mass_kg must be > 0");
    for (double i : s.inertia_kgm2)
      if (!(i > 0)) fail("body '" + s.name + "': inertia_kgm2 entries must be > 0");
    Body b{s.name, dBodyCreate(world), s.mass_kg, false, s.mass_kg};
    dBodySetPosition(b.id, s.position_m[0], s.position_m[1], s.position_m[2]);
    dMass m;
    dMassSetParameters(&m, s.mass_kg, 0, 0, 0, s.inertia_kgm2[0], s.inertia_kgm2[1],
                       s.inertia_kgm2[2], 0, 0, 0);
    dBodySetMass(b.id, &m);
    bodies.push_back(b);
  }
  for (const JointSpec& s : desc.joints) {
    Joint j{s};
    j.child = body_index(s.child);
    if (j.child < 0) fail("joint '" + s.name + "': child '" + s.child + "' is not a body");
    if (!s.parent.empty()) {
      j.parent = body_index(s.parent);
      if (j.parent < 0) fail("joint '" + s.name + "': parent '" + s.parent + "' is not a body");
    }
    for (const Joint& k : joints)
      if (k.child == j.child) fail("joint '" + s.name + "': body '" + s.child + "' already has a joint");
    if (std::hypot(s.axis[0], s.axis[1], s.axis[2]) < 1e-9) fail("joint '" + s.name + "': axis is zero");
    if (s.type == JointType::hinge && ((s.lower_stop && *s.lower_stop < -M_PI) ||
                                       (s.upper_stop && *s.upper_stop > M_PI)))
      fail("joint '" + s.name + "': hinge stops must lie within [-pi, pi]");
    joints.push_back(j);
  }
  for (Joint& j : joints) create_joint(j);

  for (const AxisSpec& s : desc.axes) {
    const std::string where = "axis '" + s.name + "': ";
    int ji = -1;
    for (std::size_t k = 0; k < joints.size(); ++k)
      if (joints[k].spec.name == s.joint) ji = static_cast<int>(k);
    if (ji < 0) fail(where + "joint '" + s.joint + "' does not exist");
    for (const Axis& other : axes)
      if (other.joint == ji) fail(where + "joint '" + s.joint + "' is already driven by another axis");
    const JointSpec& js = joints[ji].spec;
    const TransmissionSpec& t = s.transmission;
    if (!(t.ratio > 0)) fail(where + "transmission.ratio must be > 0");
    if (!(t.efficiency > 0 && t.efficiency <= 1)) fail(where + "transmission.efficiency must be in (0, 1]");
    if (t.backlash < 0 || t.stiffness < 0 || t.damping < 0)
      fail(where + "transmission backlash/stiffness/damping must be >= 0");
    if (t.kind == TransmissionKind::ball_screw && !(t.lead_m > 0)) fail(where + "transmission.lead_m must be > 0");
    if (t.kind == TransmissionKind::belt && js.type == JointType::slider && !(t.pulley_diameter_m > 0))
      fail(where + "transmission.pulley_diameter_m must be > 0 for a linear belt");
    if (is_linear(t, js.type) != (js.type == JointType::slider))
      fail(where + "transmission does not fit joint '" + js.name + "' (ball screw/linear belt need a slider)");
    if (!(s.motor.rotor_inertia_kgm2 > 0)) fail(where + "motor.rotor_inertia_kgm2 must be > 0");
    if (!(s.motor.torque_constant_nm_per_a > 0)) fail(where + "motor.torque_constant_nm_per_a must be > 0");
    if (s.encoder.counts_per_rev == 0) fail(where + "encoder.counts_per_rev must be > 0");
    if (s.brake.fitted && !(s.brake.holding_torque_nm > 0)) fail(where + "brake.holding_torque_nm must be > 0");

    const double r = load_per_motor_rad(t, js.type);
    Axis a(s, desc.step_s, js.initial / r);
    a.joint = ji;
    a.r = r;
    a.two_mass = t.stiffness > 0 || t.backlash > 0;
    if (t.backlash > 0 && t.stiffness <= 0) fail(where + "transmission.stiffness must be > 0 with backlash");
    Body& load = bodies[joints[ji].child];
    const double reflected = s.motor.rotor_inertia_kgm2 / (r * r);
    dBodyGetMass(load.id, &a.load_own);
    if (a.two_mass) {
      // The rotor is its own body on a hinge to the world (no gravity: its centre is on its axis).
      a.rotor = dBodyCreate(world);
      dBodySetPosition(a.rotor, static_cast<double>(axes.size()), -20.0, 0.0);
      const double jr = s.motor.rotor_inertia_kgm2;
      dMass m;
      dMassSetParameters(&m, 1e-3, 0, 0, 0, jr, jr, jr, 0, 0, 0);
      dBodySetMass(a.rotor, &m);
      dBodySetGravityMode(a.rotor, 0);
      a.rotor_hinge = dJointCreateHinge(world, nullptr);
      dJointAttach(a.rotor_hinge, a.rotor, nullptr);
      dJointSetHingeAnchor(a.rotor_hinge, static_cast<double>(axes.size()), -20.0, 0.0);
      dJointSetHingeAxis(a.rotor_hinge, 0, 0, 1);
      dJointSetHingeParam(a.rotor_hinge, dParamVel, 0.0);
      dJointSetHingeParam(a.rotor_hinge, dParamFMax, 0.0);
      a.rotor_angle = js.initial / r;  // zero twist at start
      // Explicit coupling spring: keep omega * dt well inside the symplectic Euler stability limit.
      dMass ml;
      dBodyGetMass(load.id, &ml);
      const double jl = load_along(ml, js);
      const double w2 = t.stiffness * (1.0 / reflected + 1.0 / jl);
      if (std::sqrt(w2) * dt > 0.5)
        fail(where + "transmission.stiffness too high for the step: raise substeps");
    } else if (js.type == JointType::hinge) {
      // Rigid: the rotor's reflected inertia is added about the joint axis of the load body.
      dMass m;
      dBodyGetMass(load.id, &m);
      const double n = std::hypot(js.axis[0], js.axis[1], js.axis[2]);
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
          m.I[i * 4 + k] += reflected * (js.axis[i] / n) * (js.axis[k] / n);
      dBodySetMass(load.id, &m);
    } else {
      // Rigid linear: reflected rotor mass moves with the load but does not weigh.
      dMass m;
      dBodyGetMass(load.id, &m);
      dMassAdjust(&m, m.mass + reflected);
      dBodySetMass(load.id, &m);
      dBodySetGravityMode(load.id, 0);
      load.manual_gravity = true;
    }
    dBodyGetMass(load.id, &a.load_full);
    axes.push_back(std::move(a));
  }

  for (const Joint& j : joints) place_initial(j);
  for (Joint& j : joints) {
    j.pos = j.spec.initial;
    j.prev_raw = j.spec.type == JointType::hinge ? dJointGetHingeAngle(j.id) : 0.0;
    read_joint(j);
  }
  for (Axis& a : axes) {
    if (a.two_mass) read_rotor(a);
    a.fb.winding_c = a.thermal.winding_c();
    a.fb.housing_c = a.thermal.housing_c();
  }
  finish_step();
  for (Axis& a : axes) a.fb.encoder = a.encoder.reading();
  find_lone_hinges();
}

void Plant::Impl::substep(double t) {
  for (Axis& a : axes) {
    Joint& j = joints[a.joint];
    const MotorParams& m = a.spec.motor;
    const TransmissionSpec& tr = a.spec.transmission;
    const bool fault_stops = a.faults.jam || a.faults.obstacle || j.fault_stops;
    if (j.lone_inertia > 0 && j.closed == fault_stops) set_closed(j, !fault_stops);  // stops: ODE's
    if (fault_stops) apply_fault_stops(a);
    const double theta = a.motor_angle(j), w = a.motor_vel(j);

    double torque;
    if (a.cmd.stepper_open_loop) {
      a.current = std::clamp(a.cmd.stepper_current, 0.0, 1.0) * m.rated_current_a;
      torque = stepper_torque(m.rated_torque_nm, std::clamp(a.cmd.stepper_current, 0.0, 1.0),
                              m.stepper_rotor_teeth, theta, a.cmd.stepper_angle_rad);
    } else {
      const double demand = std::clamp(a.cmd.torque_nm, -m.peak_torque_nm, m.peak_torque_nm);
      a.current = current_loop_step(a.current, demand / m.torque_constant_nm_per_a,
                                    m.current_bandwidth_hz, dt, a.current_lag);
      torque = m.torque_constant_nm_per_a * a.current;
      torque *= speed_taper(torque, w, m.max_speed_rad_s);
    }
    a.torque = torque;
    a.loss_j += a.current * a.current * m.winding_resistance_ohm * dt;

    const bool released = a.brake_control.value_or(a.cmd.brake_released);
    const bool braked = a.spec.brake.fitted && !released && !a.faults.brake_failure;
    const double ext = load_at(a.spec.load_profile, t) + a.ext_load + a.faults.added_force;
    double load_force = ext - a.faults.friction_scale * a.spec.friction.viscous * j.vel;
    double dry = a.faults.friction_scale * dry_friction(a.spec.friction, std::abs(j.vel));
    if (a.two_mass) {
      const double d = a.twist(j);
      double fc = tr.stiffness * d;
      if (d != 0.0) fc += tr.damping * (a.r * a.rotor_vel - j.vel);
      load_force += fc;
      dJointAddHingeTorque(a.rotor_hinge, torque - a.r * fc / tr.efficiency);
      dJointSetHingeParam(a.rotor_hinge, dParamFMax, braked ? a.spec.brake.holding_torque_nm : 0.0);
    } else {
      load_force += torque / a.r * tr.efficiency;
      if (braked) dry += a.spec.brake.holding_torque_nm / a.r;
    }
    if (j.closed) {
      lone_hinge_step(j.pos, j.vel, j.lone_inertia, load_force, dry, dt);
    } else if (j.spec.type == JointType::hinge) {
      dJointAddHingeTorque(j.id, load_force);
      dJointSetHingeParam(j.id, dParamFMax, dry);
    } else {
      dJointAddSliderForce(j.id, load_force);
      dJointSetSliderParam(j.id, dParamFMax, dry);
    }
  }
  for (const Body& b : bodies)
    if (b.manual_gravity)
      dBodyAddForce(b.id, b.own_mass * desc.gravity[0], b.own_mass * desc.gravity[1],
                    b.own_mass * desc.gravity[2]);
  if (ode_bodies_enabled == 0) return;
  dWorldStep(world, dt);
  for (Joint& j : joints)
    if (!j.closed) read_joint(j);
  for (Axis& a : axes)
    if (a.two_mass) read_rotor(a);
}

// A hinge is stepped in closed form when its body hangs from the world by it alone and carries no
// other joint, turns about a principal axis through its centre (no gravity or gyroscopic torque on
// the locked freedoms), has no machine end stops, and is driven by a rigid axis.
void Plant::Impl::find_lone_hinges() {
  ode_bodies_enabled = static_cast<int>(bodies.size());
  for (const Axis& a : axes)
    if (a.two_mass) ++ode_bodies_enabled;
  if (!desc.closed_form_hinges) return;
  for (const Axis& a : axes) {
    Joint& j = joints[a.joint];
    if (a.two_mass || j.spec.type != JointType::hinge || j.parent >= 0 || j.spec.lower_stop || j.spec.upper_stop)
      continue;
    const bool carries = std::any_of(joints.begin(), joints.end(), [&](const Joint& k) { return k.parent == j.child; });
    if (carries) continue;
    const dBodyID body = bodies[j.child].id;
    dVector3 axis, anchor;
    dJointGetHingeAxis(j.id, axis);
    dJointGetHingeAnchor(j.id, anchor);
    const dReal* p = dBodyGetPosition(body);
    const double d[3] = {p[0] - anchor[0], p[1] - anchor[1], p[2] - anchor[2]};
    if (std::hypot(d[1] * axis[2] - d[2] * axis[1], d[2] * axis[0] - d[0] * axis[2], d[0] * axis[1] - d[1] * axis[0]) > 1e-9)
      continue;
    double residual = 0;
    const double inertia = inertia_about_hinge(j.id, body, &residual);
    if (residual <= 1e-9 * inertia) j.lone_inertia = inertia;
  }
}

// Hands a lone hinge to the closed form (its ODE body disabled) or back to ODE, turning the stale
// body by what the closed form moved it and giving it the closed form's speed.
void Plant::Impl::set_closed(Joint& j, bool closed) {
  const dBodyID body = bodies[j.child].id;
  if (closed) {
    j.ode_pos = j.pos;
    dBodyDisable(body);
    --ode_bodies_enabled;
  } else {
    dVector3 n;
    dJointGetHingeAxis(j.id, n);
    dQuaternion turn, q;
    dQFromAxisAndAngle(turn, n[0], n[1], n[2], j.pos - j.ode_pos);
    dQMultiply0(q, turn, dBodyGetQuaternion(body));
    dBodySetQuaternion(body, q);
    dBodySetAngularVel(body, n[0] * j.vel, n[1] * j.vel, n[2] * j.vel);
    dBodySetLinearVel(body, 0, 0, 0);
    dBodyEnable(body);
    ++ode_bodies_enabled;
    j.prev_raw = dJointGetHingeAngle(j.id);
  }
  j.closed = closed;
}

// ODE limits on the joint in its own angle frame; +-dInfinity turns one off. Both are opened first
// so that no intermediate pair has lo > hi. ODE re-tests a limit only while a stop is finite (a
// hinge's within +-pi) and otherwise keeps the last result, so a joint left at a stop with both
// turned off would keep a stale limit row (an LCP assertion): an "off" low stop is therefore a
// finite one the load cannot reach (hinge: -pi, never below the angle's range; slider: -1e30).
void Plant::Impl::set_stops(const Joint& j, double lo, double hi) {
  const bool hinge = j.spec.type == JointType::hinge;
  if (lo == -dInfinity) lo = hinge ? -M_PI : -1e30;
  auto set = [&](int param, double v) {
    if (hinge) dJointSetHingeParam(j.id, param, v);
    else dJointSetSliderParam(j.id, param, v);
  };
  set(dParamLoStop, -dInfinity);
  set(dParamHiStop, dInfinity);
  set(dParamLoStop, lo);
  set(dParamHiStop, hi);
}

// Jam and obstacle as joint stops, each substep. The tightest of the machine's end stops, the
// obstacle and the jam lock wins on each side. ODE measures a hinge's angle in (-pi, pi] and takes
// stops only inside it, while a load may have turned many times: the hinge's angle frame is moved
// (dJointSetHingeAxisOffset) so the load sits within pi/2 of the frame's zero, and a stop further
// than pi/2 - margin away is left off until the load comes nearer (it moves far less per substep).
void Plant::Impl::apply_fault_stops(Axis& a) {
  Joint& j = joints[a.joint];
  const bool hinge = j.spec.type == JointType::hinge;
  const bool active = a.faults.jam || a.faults.obstacle.has_value();
  if (!active) {  // faults gone: the machine's own stops in the original frame (raw = q mod 2 pi)
    if (hinge) {
      dVector3 ax;
      dJointGetHingeAxis(j.id, ax);
      dJointSetHingeAxisOffset(j.id, ax[0], ax[1], ax[2], wrap_pi(j.pos));
      j.prev_raw = dJointGetHingeAngle(j.id);
    }
    set_stops(j, j.spec.lower_stop ? *j.spec.lower_stop : -dInfinity,
              j.spec.upper_stop ? *j.spec.upper_stop : dInfinity);
    j.fault_stops = false;
    return;
  }
  double lo = j.spec.lower_stop ? *j.spec.lower_stop : -dInfinity;
  double hi = j.spec.upper_stop ? *j.spec.upper_stop : dInfinity;
  if (const auto& o = a.faults.obstacle) {
    if (a.obstacle_above) hi = std::min(hi, *o);
    else lo = std::max(lo, *o);
  }
  if (a.faults.jam) lo = hi = a.lock_at;
  j.fault_stops = true;
  if (!hinge) {
    set_stops(j, lo, hi);
    return;
  }
  double raw = dJointGetHingeAngle(j.id);
  if (std::abs(raw) > 0.5 * M_PI) {
    dVector3 ax;
    dJointGetHingeAxis(j.id, ax);
    dJointSetHingeAxisOffset(j.id, ax[0], ax[1], ax[2], 0.0);
    raw = dJointGetHingeAngle(j.id);
    j.prev_raw = raw;
  }
  constexpr double margin = 0.05;
  const double reach = M_PI - margin;
  const double lo_raw = lo - j.pos + raw, hi_raw = hi - j.pos + raw;
  set_stops(j, lo_raw > -reach ? lo_raw : -dInfinity, hi_raw < reach ? hi_raw : dInfinity);
}

// The load body's own mass and inertia times `scale`, the reflected rotor part unchanged.
void Plant::Impl::scale_load(Axis& a, double scale) {
  Joint& j = joints[a.joint];
  Body& body = bodies[j.child];
  dMass m = a.load_full;
  m.mass = a.load_own.mass * scale + (a.load_full.mass - a.load_own.mass);
  for (int i = 0; i < 12; ++i) m.I[i] = a.load_own.I[i] * scale + (a.load_full.I[i] - a.load_own.I[i]);
  dBodySetMass(body.id, &m);
  body.own_mass = body.base_mass * scale;
  if (j.lone_inertia > 0) j.lone_inertia = inertia_about_hinge(j.id, body.id);
}

void Plant::Impl::finish_step() {
  for (Axis& a : axes) {
    const Joint& j = joints[a.joint];
    const MotorParams& m = a.spec.motor;
    AxisFeedback& fb = a.fb;
    a.thermal.step(a.loss_j / desc.step_s);
    a.loss_j = 0;
    fb.motor_angle_rad = a.motor_angle(j);
    fb.motor_velocity_rad_s = a.motor_vel(j);
    a.encoder.update(fb.motor_angle_rad);
    fb.encoder = a.encoder.reading();
    fb.load_position = j.pos;
    fb.load_velocity = j.vel;
    fb.torque_nm = a.torque;
    fb.current_a = a.current;
    fb.winding_c = a.thermal.winding_c();
    fb.housing_c = a.thermal.housing_c();

    const SwitchSpec& sw = a.spec.switches;
    const double q = j.pos;
    auto inside = [q](const std::optional<PositionWindow>& w) { return w && q >= w->from && q <= w->to; };
    std::uint32_t in = 0;
    if (sw.negative_limit && q <= *sw.negative_limit) in |= input::negative_limit;
    if (sw.positive_limit && q >= *sw.positive_limit) in |= input::positive_limit;
    if (inside(sw.home)) in |= input::home;
    if (inside(sw.probe1)) in |= input::probe1;
    if (inside(sw.probe2)) in |= input::probe2;
    a.sensor_inputs = in;
    fb.inputs = in | a.ext_inputs;

    constexpr double stop_tolerance = 1e-4;
    if (fb.winding_c > m.winding_limit_c) fb.faults |= fault::overtemperature;
    if (std::abs(fb.motor_velocity_rad_s) > 1.2 * m.max_speed_rad_s) fb.faults |= fault::overspeed;
    if ((j.spec.lower_stop && q <= *j.spec.lower_stop + stop_tolerance) ||
        (j.spec.upper_stop && q >= *j.spec.upper_stop - stop_tolerance))
      fb.faults |= fault::end_stop;
    if (const auto& o = a.faults.obstacle;
        o && (a.obstacle_above ? q >= *o - stop_tolerance : q <= *o + stop_tolerance))
      fb.faults |= fault::end_stop;   // against the obstacle (AxisFaults::obstacle)
    fb.lost_steps = a.cmd.stepper_open_loop
                        ? stepper_lost_steps(m.stepper_rotor_teeth, fb.motor_angle_rad, a.cmd.stepper_angle_rad)
                        : 0;
    if (fb.lost_steps != 0) fb.faults |= fault::lost_steps;
  }
}

Plant::Plant(const PlantDescription& description) : impl_(std::make_unique<Impl>()) {
  ensure_ode();
  impl_->desc = description;
  impl_->build();
}
Plant::~Plant() = default;
Plant::Plant(Plant&&) noexcept = default;
Plant& Plant::operator=(Plant&&) noexcept = default;

std::size_t Plant::axis_count() const { return impl_->axes.size(); }

std::optional<std::size_t> Plant::axis_index(std::string_view name) const {
  for (std::size_t i = 0; i < impl_->axes.size(); ++i)
    if (impl_->axes[i].spec.name == name) return i;
  return std::nullopt;
}

void Plant::command(std::size_t axis, const AxisCommand& cmd) { impl_->axes.at(axis).cmd = cmd; }
const AxisFeedback& Plant::feedback(std::size_t axis) const { return impl_->axes.at(axis).fb; }

void Plant::step() {
  ensure_ode_thread_data();
  Impl& p = *impl_;
  const double t0 = static_cast<double>(p.steps) * p.desc.step_s;
  for (int s = 0; s < p.desc.substeps; ++s) p.substep(t0 + s * p.dt);
  ++p.steps;
  p.finish_step();
}

std::size_t Plant::advance_to(Nanos t) {
  std::size_t n = 0;
  while ((impl_->steps + 1) * impl_->step_ns <= t) {
    step();
    ++n;
  }
  return n;
}

Nanos Plant::time() const { return impl_->steps * impl_->step_ns; }
double Plant::step_s() const { return impl_->desc.step_s; }

void Plant::set_external_load(std::size_t axis, double force) { impl_->axes.at(axis).ext_load = force; }
// Takes effect in the feedback at once, as a switch wired in parallel to the sensor would.
void Plant::set_external_input(std::size_t axis, std::uint32_t bits) {
  auto& a = impl_->axes.at(axis);
  a.ext_inputs = bits;
  a.fb.inputs = a.sensor_inputs | bits;
}
std::uint32_t Plant::external_input(std::size_t axis) const { return impl_->axes.at(axis).ext_inputs; }
const AxisCommand& Plant::last_command(std::size_t axis) const { return impl_->axes.at(axis).cmd; }
void Plant::set_brake_control(std::size_t axis, std::optional<bool> released) {
  impl_->axes.at(axis).brake_control = released;
}
void Plant::clear_faults(std::size_t axis) { impl_->axes.at(axis).fb.faults = 0; }

void Plant::set_axis_faults(std::size_t axis, const AxisFaults& f) {
  Impl& p = *impl_;
  Impl::Axis& a = p.axes.at(axis);
  const Impl::Joint& j = p.joints[a.joint];
  const std::string where = "axis '" + a.spec.name + "': ";
  if (!(f.load_scale > 0) || !std::isfinite(f.load_scale)) fail(where + "load_scale must be a finite number > 0");
  if (!std::isfinite(f.added_force)) fail(where + "added_force must be finite");
  if (!(f.friction_scale >= 0) || !std::isfinite(f.friction_scale)) fail(where + "friction_scale must be a finite number >= 0");
  if (f.obstacle && !std::isfinite(*f.obstacle)) fail(where + "obstacle must be finite");
  if (f.load_scale != a.faults.load_scale) {
    if (a.two_mass) {  // the explicit coupling spring must stay stable with the lighter load (see build)
      const TransmissionSpec& t = a.spec.transmission;
      const double jl = load_along(a.load_own, j.spec) * f.load_scale;
      const double reflected = a.spec.motor.rotor_inertia_kgm2 / (a.r * a.r);
      if (std::sqrt(t.stiffness * (1.0 / reflected + 1.0 / jl)) * p.dt > 0.5)
        fail(where + "load_scale makes the transmission too stiff for the step: raise substeps");
    }
    p.scale_load(a, f.load_scale);
  }
  if (f.jam && !a.faults.jam) a.lock_at = j.pos;   // seized where it is now
  if (f.obstacle && (!a.faults.obstacle || *a.faults.obstacle != *f.obstacle))
    a.obstacle_above = j.pos < *f.obstacle || (j.pos == *f.obstacle && j.vel >= 0);   // the side it comes from
  a.faults = f;
}

const AxisFaults& Plant::axis_faults(std::size_t axis) const { return impl_->axes.at(axis).faults; }

double Plant::energy() const {
  const Impl& p = *impl_;
  double e = 0;
  auto kinetic = [](dBodyID id) {
    dMass m;
    dBodyGetMass(id, &m);
    const dReal* v = dBodyGetLinearVel(id);
    const dReal* w = dBodyGetAngularVel(id);
    const dReal* r = dBodyGetRotation(id);
    // Angular momentum in body frame: I (R^T w).
    double wb[3];
    for (int i = 0; i < 3; ++i) wb[i] = r[0 * 4 + i] * w[0] + r[1 * 4 + i] * w[1] + r[2 * 4 + i] * w[2];
    double rot = 0;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) rot += wb[i] * m.I[i * 4 + k] * wb[k];
    return 0.5 * m.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * rot;
  };
  // ODE's velocities after a step belong half a step back (its integrator is a leapfrog: v then
  // x with the new v). Potential energy is therefore taken at x - v dt/2, where the velocities
  // live; otherwise the readout would wobble by ~w*dt/2 although the motion conserves energy.
  const double half = 0.5 * p.dt;
  for (const Impl::Joint& j : p.joints)
    if (j.closed) e += 0.5 * j.lone_inertia * j.vel * j.vel;  // its ODE body is stale, and at rest in place
  for (const Impl::Body& b : p.bodies) {
    const bool closed = !dBodyIsEnabled(b.id);  // only the closed form disables a body
    if (!closed) e += kinetic(b.id);
    const dReal* x = dBodyGetPosition(b.id);
    const dReal* v = dBodyGetLinearVel(b.id);
    double pe = 0;  // a closed-form body's centre is at rest on its axis
    for (int i = 0; i < 3; ++i) pe -= b.own_mass * p.desc.gravity[i] * (x[i] - (closed ? 0.0 : v[i] * half));
    e += pe;
  }
  for (const Impl::Axis& a : p.axes) {
    if (!a.two_mass) continue;
    e += kinetic(a.rotor);
    const Impl::Joint& j = p.joints[a.joint];
    const double twist = a.r * (a.rotor_angle - a.rotor_vel * half) - (j.pos - j.vel * half);
    const double h = 0.5 * a.spec.transmission.backlash;
    const double d = twist > h ? twist - h : twist < -h ? twist + h : 0.0;
    e += 0.5 * a.spec.transmission.stiffness * d * d;
  }
  return e;
}

}  // namespace vdrive::plant
