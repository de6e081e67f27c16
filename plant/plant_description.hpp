#pragma once
// A plant described as data: ODE bodies and joints (the machine), and one axis per drive (motor,
// transmission, friction, encoder, brake, switches, external load). Built by the YAML loader
// (plant_yaml.hpp) or by default_plant() for a product; turned into a running world by Plant.
// Units are SI. "Load units" are rad for a hinge joint and m for a slider joint.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vdrive::plant {

using Vec3 = std::array<double, 3>;

// A rigid body. Its origin is its centre of mass; inertia is principal, axes aligned with the world
// frame in the zero configuration (all joint positions 0).
struct BodySpec {
  std::string name;
  double mass_kg = 1.0;
  Vec3 position_m{0, 0, 0};
  Vec3 inertia_kgm2{1e-3, 1e-3, 1e-3};
};

enum class JointType { hinge, slider };

// One degree of freedom between `parent` ("" = the fixed world) and `child`, defined in the zero
// configuration; `initial` is where the joint starts. Limits are hard end stops (ODE joint stops).
struct JointSpec {
  std::string name;
  JointType type = JointType::hinge;
  std::string parent;
  std::string child;
  Vec3 anchor_m{0, 0, 0};
  Vec3 axis{0, 0, 1};
  std::optional<double> lower_stop, upper_stop;
  double stop_bounce = 0.0;  // restitution at the end stops (0 = plastic hit)
  double initial = 0.0;
};

enum class MotorKind { servo, stepper };

// Everything the physics needs to know about one motor, as plain values (a product's catalogue
// entry becomes one above the plant, in vdrive/drive/product_plant.hpp).
struct MotorParams {
  std::string model;
  MotorKind kind = MotorKind::servo;
  double torque_constant_nm_per_a = 0.4;
  double rotor_inertia_kgm2 = 1.4e-5;
  double winding_resistance_ohm = 1.0;    // effective, copper loss = i^2 R
  double winding_inductance_h = 2e-3;
  double current_bandwidth_hz = 2000.0;   // closed current loop, first order
  double rated_torque_nm = 0.64;          // continuous (servo) / holding torque at rated current (stepper)
  double peak_torque_nm = 1.91;
  double rated_current_a = 1.6;
  double max_speed_rad_s = 628.3;         // back-EMF limit: torque tapers to 0 over the next 10 %
  // Thermal RC network (winding -> housing -> ambient).
  double ambient_c = 25.0;
  double winding_capacity_j_per_k = 60.0;
  double housing_capacity_j_per_k = 600.0;
  double winding_to_housing_k_per_w = 1.0;
  double housing_to_ambient_k_per_w = 3.0;
  double winding_limit_c = 130.0;         // overload fault above this
  // Stepper: rotor teeth (50 for a 1.8 deg hybrid stepper: one electrical cycle = 4 full steps).
  int stepper_rotor_teeth = 50;
};

enum class TransmissionKind { direct, gearbox, belt, ball_screw };

// Motor -> load. ratio = motor turns per output (pulley/screw/gear) turn. Rigid unless stiffness > 0
// or backlash > 0: then the rotor is its own body, coupled by a spring with a dead zone (two-mass).
struct TransmissionSpec {
  TransmissionKind kind = TransmissionKind::direct;
  double ratio = 1.0;
  double pulley_diameter_m = 0.0;  // belt driving a slider (linear belt axis)
  double lead_m = 0.0;             // ball screw lead per screw turn
  double efficiency = 1.0;
  double backlash = 0.0;           // total dead zone width, load units
  double stiffness = 0.0;          // coupling stiffness, N m/rad or N/m at the load; 0 = rigid
  double damping = 0.0;            // coupling damping, load units per second
};

// Load-side friction: Stribeck curve F(v) = Fc + (Fs - Fc) exp(-(v/vs)^2) + b v, and the joint
// holds (sticks) until the applied force exceeds Fs.
struct FrictionSpec {
  double coulomb = 0.0;
  double breakaway = 0.0;          // static; 0 = same as coulomb
  double stribeck_velocity = 0.01;
  double viscous = 0.0;
};

struct EncoderSpec {
  std::uint32_t counts_per_rev = 8388608;  // on the motor shaft
  bool absolute = true;                    // incremental encoders count from 0 at power-on
  unsigned multiturn_bits = 16;            // 0 = single-turn
  double index_angle_rad = 0.0;            // motor angle of the once-per-turn index mark
};

struct BrakeSpec {
  bool fitted = false;
  double holding_torque_nm = 0.0;  // on the motor shaft
};

// A switch that is on while the load position is inside [from, to].
struct PositionWindow {
  double from = 0.0, to = 0.0;
};

struct SwitchSpec {
  std::optional<double> negative_limit;  // on at or below
  std::optional<double> positive_limit;  // on at or above
  std::optional<PositionWindow> home;
  std::optional<PositionWindow> probe1, probe2;
};

struct AxisSpec {
  std::string name;
  MotorParams motor;
  std::string joint;                     // "" = the axis gets its own inertia on a hinge
  double load_inertia_kgm2 = 0.0;        // for joint == "": load inertia (0 = equal to rotor's)
  TransmissionSpec transmission;
  FrictionSpec friction;
  EncoderSpec encoder;
  BrakeSpec brake;
  SwitchSpec switches;
  std::vector<std::pair<double, double>> load_profile;  // (time s, force/torque in load units), linear
};

struct PlantDescription {
  double step_s = 250e-6;  // the period the caller advances in
  int substeps = 2;        // ODE steps per step
  // A lone body on a hinge driven by a rigid axis (every default plant) is stepped in closed form,
  // the step ODE would take (lone_hinge_step.hpp), while no jam or obstacle is on it; false = ODE
  // steps everything (the tests compare the two).
  bool closed_form_hinges = true;
  Vec3 gravity{0, 0, -9.81};
  std::vector<BodySpec> bodies;
  std::vector<JointSpec> joints;
  std::vector<AxisSpec> axes;
};

}  // namespace vdrive::plant
