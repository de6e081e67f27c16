#pragma once
// Vocabulary shared by the parts of the CiA402 drive engine (IEC 61800-7-201 / CiA 402): the power
// drive system states, the mode numbers of 6060h, what the drive measured in a control step and
// what a mode asks of the control loops. Positions are in user units (6064h), velocities in user
// units/s (606Ch), torques in 0.1 % of rated torque (6077h), all after polarity (607Eh).
#include <cstdint>

#include "common/clock.hpp"

namespace vdrive::drive {

enum class PdsState : std::uint8_t {
  NotReadyToSwitchOn,
  SwitchOnDisabled,
  ReadyToSwitchOn,
  SwitchedOn,
  OperationEnabled,
  QuickStopActive,
  FaultReactionActive,
  Fault,
};

namespace mode {  // 6060h / 6061h values
inline constexpr std::int8_t none = 0, pp = 1, vl = 2, pv = 3, tq = 4, hm = 6, ip = 7, csp = 8, csv = 9,
                             cst = 10;
}  // namespace mode

namespace cw {  // 6040h bits
inline constexpr std::uint16_t switch_on = 1u << 0, enable_voltage = 1u << 1, quick_stop = 1u << 2,
                               enable_operation = 1u << 3, new_set_point = 1u << 4,  // pp; hm start; ip enable
    change_set_immediately = 1u << 5, relative = 1u << 6, fault_reset = 1u << 7, halt = 1u << 8,
                               change_on_set_point = 1u << 9;
}  // namespace cw

namespace sw {  // 6041h bits
inline constexpr std::uint16_t ready_to_switch_on = 1u << 0, switched_on = 1u << 1, operation_enabled = 1u << 2,
                               fault = 1u << 3, voltage_enabled = 1u << 4, quick_stop = 1u << 5,
                               switch_on_disabled = 1u << 6, warning = 1u << 7, remote = 1u << 9,
                               target_reached = 1u << 10, internal_limit = 1u << 11, oms12 = 1u << 12,
                               oms13 = 1u << 13;
inline constexpr std::uint16_t mode_bits = target_reached | oms12 | oms13;  // what a mode owns
}  // namespace sw

// Plant inputs as the drive sees them this step (already through the product's input logic).
namespace din {
inline constexpr std::uint32_t negative_limit = 1u << 0, positive_limit = 1u << 1, home = 1u << 2,
                               probe1 = 1u << 3, probe2 = 1u << 4, torque_off = 1u << 5;
}  // namespace din

// One control step as measured, in user units.
struct AxisSample {
  Nanos time = 0;                  // end of this step
  double dt_s = 0.0;               // control period
  double position = 0.0;           // 6064h before rounding
  double velocity = 0.0;           // 606Ch
  double torque = 0.0;             // 6077h, 0.1 % of rated
  double position_demand = 0.0;    // 6062h as commanded in the previous step
  double velocity_demand = 0.0;    // 606Bh as commanded in the previous step
  double torque_demand = 0.0;      // 6074h of the previous step
  std::uint32_t inputs = 0;        // din:: bits
  bool index_passed = false;       // the encoder index mark was crossed during the step
  double index_position = 0.0;     // position (user) where it was crossed
  bool stopped = false;            // |speed| <= the product's "stopped" speed
  bool referenced = false;         // position is referenced (absolute encoder, or homed)
};

// What a mode or a stop ramp asks of the control loops for one step.
struct Setpoint {
  enum class Kind : std::uint8_t { Position, Velocity, Torque } kind = Kind::Position;
  double position = 0.0;           // Position: demand (user)
  double velocity = 0.0;           // Velocity: demand; Position: feed-forward (user/s)
  double torque = 0.0;             // Torque: demand; others: feed-forward (0.1 %)
  double torque_limit = 0.0;       // extra torque limit for this step (0.1 %); 0 = none (hard-stop homing)
};

}  // namespace vdrive::drive
