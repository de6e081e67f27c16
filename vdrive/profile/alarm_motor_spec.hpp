#pragma once
// A product's alarm table (profiles/<id>/alarms.yaml) and motor catalogue (motors.yaml).
#include <cstdint>
#include <string>

namespace vdrive::profile {

// What the drive does to the motor when the alarm occurs.
enum class AlarmReaction : std::uint8_t {
  None,            // no motor reaction (communication alarm only; PDS unchanged)
  ImmediateStop,   // immediate stop (torque-limited stop / dynamic brake)
  Deceleration,    // decelerate to stop, then disable
  FreeRun,         // power stage off at once, motor coasts
};

struct AlarmSpec {
  std::string code;                                   // vendor display code as printed: "80.4", "E-804", "FF01h"
  std::string name;                                   // original-language name as printed
  std::string name_en;                                // English
  std::uint16_t error_code = 0;                       // 603Fh value while active
  std::uint16_t emergency_code = 0;                   // error code sent in the EMCY message
  bool clearable = true;                              // can be reset by fault reset / alarm clear
  AlarmReaction reaction = AlarmReaction::None;
  std::uint16_t al_status_code = 0;                   // 0 = no AL status code
  bool history = true;                                // kept in the alarm history (10F3h / vendor list)
  bool warning = false;                               // a warning, not an alarm (no Fault state)
  std::string source;                                 // manual line(s), e.g. "L32567"
};

// A motor of the product's catalogue. Absent values are 0 (the manual does not give them).
struct MotorSpec {
  std::string model;
  std::string condition;                              // when ratings depend on it, e.g. "24 V supply" ("" = none)
  std::string source;                                 // manual line(s)
  double rated_power_w = 0;
  double rated_torque_nm = 0;                         // continuous (servo) or holding torque (stepper)
  double peak_torque_nm = 0;
  double rated_speed_rpm = 0;
  double max_speed_rpm = 0;
  double rated_current_a = 0;                         // rms (servo) / per phase (stepper)
  double torque_constant_nm_per_a = 0;
  double rotor_inertia_kgm2 = 0;                      // SI units (manuals print x10^-4 kg m^2 or g cm^2)
  std::uint32_t encoder_counts_per_rev = 0;
};

}  // namespace vdrive::profile
