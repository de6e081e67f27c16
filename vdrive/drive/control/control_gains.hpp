#pragma once
// The servo cascade's gains in SI units, read from the vendor parameters profile.drive.gains names
// (A6B Pr1.00-Pr1.04 / Pr0.04, DS5C1 P1-00..P1-02 / P2-35 / P0-07, DS1000A-EC 2100h..). The
// discrete model follows the DS5C1 manual's definitions (xinje-ds5c1 digest §9.4):
//   velocity loop  T = Kv (e_w + (1/Ti) integral e_w dt),  Kv = J_tot 2 pi f_v,
//   J_tot = J_rotor (1 + inertia ratio)   (P0-07, L8658; P1-00 x P1-01 ~ 636620, L6686)
//   position loop  w_ref = Kp e_theta + k_ff w_ff.
#include "plant/plant_description.hpp"
#include "vdrive/drive/parameter_value.hpp"
#include "vdrive/drive/drive_context.hpp"

namespace vdrive::drive {

struct ControlGains {
  double position_gain = 0.0;        // Kp, 1/s
  double velocity_bandwidth_hz = 0;  // f_v
  double velocity_integral_s = 0.0;  // Ti; <= 0: no integral action
  double torque_filter_s = 0.0;      // first-order torque command filter; <= 0: none
  double inertia_ratio = 0.0;        // load / rotor
  double velocity_feedforward = 0.0; // 0..1
  double velocity_gain = 0.0;        // Kv, N m s/rad (derived)
};

// Used where a product's profile names no parameter for a gain (and gives no fallback): a stiff,
// well-damped tuning for the default plant (load inertia = rotor inertia), f_v = 40 Hz,
// Kp = 2 pi f_v / 4, Ti = 2 / (pi f_v) as the DS5C1 pairs them (L6686).
namespace engine_default_gains {
inline constexpr double velocity_bandwidth_hz = 40.0;
inline constexpr double position_gain = 2.0 * 3.141592653589793 * velocity_bandwidth_hz / 4.0;
inline constexpr double velocity_integral_s = 2.0 / (3.141592653589793 * velocity_bandwidth_hz);
inline constexpr double torque_filter_s = 0.3e-3;
inline constexpr double inertia_ratio = 1.0;
inline constexpr double velocity_feedforward = 1.0;
}  // namespace engine_default_gains

// The gain parameters of one drive, resolved at construction; read() takes their current values
// (at power stage on: a real drive latches gain changes at its own pace, here at reset()).
class ControlGainSource {
public:
  ControlGainSource(const DriveContext& ctx, const plant::MotorParams& motor);
  ControlGains read() const;

private:
  double rotor_inertia_;
  ParameterValue kp_, fv_, ti_, tf_, ratio_, kff_;
};

}  // namespace vdrive::drive
