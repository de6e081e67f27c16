#include "vdrive/drive/product_plant.hpp"

#include <cmath>

namespace vdrive::drive {

using plant::AxisSpec;
using plant::MotorKind;
using plant::MotorParams;
using plant::PlantDescription;

namespace {

constexpr double kRpm = 2.0 * M_PI / 60.0;

// Thermal network scaled so that rated current gives an 80 K steady winding rise, with a winding
// time constant of 1 min and a housing time constant of 30 min.
void fill_thermal(MotorParams& m) {
  const double loss = m.rated_current_a * m.rated_current_a * m.winding_resistance_ohm;
  const double total = 80.0 / loss;
  m.winding_to_housing_k_per_w = 0.25 * total;
  m.housing_to_ambient_k_per_w = 0.75 * total;
  m.winding_capacity_j_per_k = 60.0 / m.winding_to_housing_k_per_w;
  m.housing_capacity_j_per_k = 1800.0 / m.housing_to_ambient_k_per_w;
}

}  // namespace

MotorParams motor_params_from(const profile::MotorSpec& s, const profile::DriveSpec& drive) {
  MotorParams m;
  m.model = s.model;
  const double rated_speed = (s.rated_speed_rpm > 0 ? s.rated_speed_rpm : 3000.0) * kRpm;
  if (drive.stepper) {
    m.kind = MotorKind::stepper;
    m.rated_torque_nm = s.rated_torque_nm > 0 ? s.rated_torque_nm : 0.3;
    m.peak_torque_nm = s.peak_torque_nm > 0 ? s.peak_torque_nm : m.rated_torque_nm;
    // Rotor inertia of the frame size (typical NEMA 11 / NEMA 17 hybrid steppers).
    const bool small = s.model.find("STM28") != std::string::npos;
    m.rotor_inertia_kgm2 = s.rotor_inertia_kgm2 > 0 ? s.rotor_inertia_kgm2 : (small ? 9e-7 : 3.8e-6);
    m.rated_current_a = s.rated_current_a > 0 ? s.rated_current_a : (small ? 1.0 : 2.0);
    m.current_bandwidth_hz = 1000.0;
    m.max_speed_rad_s = (s.max_speed_rpm > 0 ? s.max_speed_rpm : 3000.0) * kRpm;
  } else {
    m.kind = MotorKind::servo;
    if (s.rated_torque_nm > 0) m.rated_torque_nm = s.rated_torque_nm;
    else if (s.rated_power_w > 0) m.rated_torque_nm = s.rated_power_w / rated_speed;
    else m.rated_torque_nm = 0.64;  // 200 W, 3000 r/min
    m.peak_torque_nm = s.peak_torque_nm > 0 ? s.peak_torque_nm : 3.0 * m.rated_torque_nm;
    // Low-inertia servo motors accelerate at about 45 000 rad/s^2 with rated torque.
    m.rotor_inertia_kgm2 = s.rotor_inertia_kgm2 > 0 ? s.rotor_inertia_kgm2 : m.rated_torque_nm / 45000.0;
    m.max_speed_rad_s = s.max_speed_rpm > 0 ? s.max_speed_rpm * kRpm : 2.0 * rated_speed;
    m.current_bandwidth_hz = 2000.0;
    const double kt = s.torque_constant_nm_per_a > 0 ? s.torque_constant_nm_per_a
                      : s.rated_current_a > 0     ? m.rated_torque_nm / s.rated_current_a
                                                  : 0.5 * std::sqrt(m.rated_torque_nm);
    m.rated_current_a = s.rated_current_a > 0 ? s.rated_current_a : m.rated_torque_nm / kt;
  }
  m.torque_constant_nm_per_a = s.torque_constant_nm_per_a > 0 ? s.torque_constant_nm_per_a
                                                              : m.rated_torque_nm / m.rated_current_a;
  // Copper loss at rated load ~10 % of rated mechanical power.
  m.winding_resistance_ohm =
      0.1 * m.rated_torque_nm * rated_speed / (m.rated_current_a * m.rated_current_a);
  m.winding_inductance_h = m.winding_resistance_ohm / (2.0 * M_PI * 200.0);  // L/R = 0.8 ms
  fill_thermal(m);
  return m;
}

MotorParams default_motor(const profile::ProductProfile& product) {
  if (!product.motors.empty()) return motor_params_from(product.motors.front(), product.drive);
  return motor_params_from(profile::MotorSpec{}, product.drive);
}

PlantDescription default_plant(const profile::ProductProfile& product) {
  PlantDescription d;
  AxisSpec a;
  a.name = product.id.empty() ? "axis" : product.id;
  a.motor = default_motor(product);
  a.load_inertia_kgm2 = a.motor.rotor_inertia_kgm2;
  a.friction.coulomb = 0.01 * a.motor.rated_torque_nm;
  a.friction.breakaway = 0.015 * a.motor.rated_torque_nm;
  a.friction.viscous = 1e-5 * a.motor.rated_torque_nm;
  const bool stepper = a.motor.kind == MotorKind::stepper;
  std::uint32_t cpr = product.motors.empty() ? 0 : product.motors.front().encoder_counts_per_rev;
  a.encoder.counts_per_rev = cpr > 0 ? cpr : (stepper ? 10000 : 8388608);
  a.encoder.absolute = !stepper;
  a.encoder.multiturn_bits = stepper ? 0 : 16;
  d.axes.push_back(std::move(a));
  return d;
}

plant::MotorCatalogue motor_catalogue(const profile::ProductProfile& product) {
  plant::MotorCatalogue c;
  c.default_motor = default_motor(product);
  c.motors.reserve(product.motors.size());
  for (const profile::MotorSpec& s : product.motors) c.motors.push_back(motor_params_from(s, product.drive));
  return c;
}

}  // namespace vdrive::drive
