#pragma once
// How a product's CiA 402 drive behaves (profile.yaml key `drive`): control period, gains and levels
// from vendor parameters, the vendor alarm for each cause, and the rules where products differ.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "vdrive/profile/product_rules.hpp"

namespace vdrive::profile {

// One vendor parameter the drive reads a control-loop setting from, e.g. A6B Pr1.00 = 3100h
// (0.1/s). SI value = raw * scale; `fallback` (SI) when the product has no such object or it reads 0.
struct ParameterRef {
  std::uint16_t index = 0;                            // 0 = the product has none
  std::uint8_t subindex = 0;
  double scale = 1.0;
  double fallback = 0.0;
};

// Where the drive's control loops take their gains from.
struct ControlGainSpec {
  ParameterRef position_gain;                         // Kp, 1/s
  ParameterRef velocity_gain;                         // velocity-loop bandwidth, Hz
  ParameterRef velocity_integral;                     // velocity-loop integral time constant, s
  ParameterRef torque_filter;                         // torque command filter time constant, s
  ParameterRef inertia_ratio;                         // load / rotor inertia, as a ratio (1.0 = 100 %)
  ParameterRef velocity_feedforward;                  // 0..1
};

// The vendor alarm ("24.0", "E-100", "FF02h") the drive raises for each cause it can detect in
// simulation; "" = the product has no alarm for it (the cause then only shows in the statusword).
struct DriveAlarmCauses {
  std::string following_error;                        // position deviation beyond the alarm level
  std::string overspeed;                              // motor speed beyond the overspeed level
  std::string overload;                               // motor overload (thermal / I^2 t)
  std::string overtemperature;                        // drive or motor over-temperature
  std::string esm_change_while_enabled;               // ESM left Op while Operation enabled
  std::string no_mode_at_enable;                      // enable with 6060h = 6061h = 0 / bad mode
  std::string position_command_jump;                  // csp set-point step beyond the speed limit
  std::string position_range;                         // 607Ah outside 607Bh
  std::string limit_switch;                           // POT/NOT reached (products that alarm)
  std::string both_limit_switches;                    // both limits active / wrong direction
  std::string homing_error;                           // products with a homing alarm
  std::string encoder_error;                          // encoder communication lost
  std::string overvoltage;                            // DC bus over-voltage
  std::string undervoltage;                           // DC bus (PN) under-voltage
  std::string main_power_off;                         // main (power-stage) supply switched off
  std::string abort_connection;                       // main power lost while enabled with 6007h = 1
  // undervoltage / main_power_off are detected only while the power stage is on (servo on); with
  // the servo off the loss shows in 6041h bit 4 alone (A6B). false: detected in any state.
  bool supply_alarms_only_when_enabled = false;
};

enum class SoftLimitRule : std::uint8_t {
  Always,          // 607Dh acts whenever min < max (A6B once the position is established)
  AfterHoming,     // 607Dh acts only after a successful homing (DS1000A-EC, A6B incremental)
  Ignored,         // listed in the dictionary but not enforced (DS5C1)
};

enum class PositionRangeRule : std::uint8_t {
  Full,            // 80000000h..7FFFFFFFh, no wrap (A6B default, DS5C1: 607Bh ignored)
  Wrap,            // 6064h wraps between 607Bh-01h and -02h when they differ (DS1000A-EC)
};

enum class LimitSwitchRule : std::uint8_t {
  QuickStop,       // stop with the quick-stop ramp and refuse motion into the limit (no alarm)
  Alarm,           // raise DriveAlarmCauses::limit_switch
  ReportOnly,      // only shown in 60FDh
};

enum class BrakeRule : std::uint8_t {
  Automatic,       // the drive releases the brake on enable and engages it on disable
  Master,          // 60FEh-01h bit 0 under the 60FEh-02h mask (DS1000A-EC)
};

// Vendor levels the drive's own supervision uses.
struct DriveLevelSpec {
  ParameterRef following_error;                       // alarm level (A6B 3014h Pr0.14, DS5C1 P0-23, DS1000A 2108h)
  bool following_error_in_increments = false;         // level in encoder increments (else user units)
  bool following_error_in_revolutions = false;        // level in motor revolutions (DS5C1 P0-23, 0.01 rev)
  ParameterRef overspeed_rpm;                         // overspeed alarm level, r/min (0 / none: overspeed_factor * 6080h)
  ParameterRef overspeed_reverse_rpm;                 // reverse-direction level where the product has one (DS5C1 P3-22); none: overspeed_rpm
  ParameterRef overload;                              // servo I^2 t: load factor (1.0 = rated torque, continuous) that trips; 0: not supervised
  double overload_time_constant_s = 0.0;              // thermal time constant of the load factor
};

// The DS1000A-EC's closed-loop stepper settings (210Dh-2113h).
struct StepperSpec {
  ParameterRef loop_mode;                             // 0 closed, 1 open below switch speed, 2 open
  ParameterRef switch_speed_rpm;                      // open/closed switch speed
  ParameterRef run_current;                           // open-loop current, as a fraction of rated (scale to 0..1)
};

// Profile position (pp) set-point handling where the products differ.
struct ProfilePositionSpec {
  bool buffered_set_point = true;       // one set-point waits behind the executing one (A6B L15728-L15757);
                                        // false: a set-point given during a move without bit 5 is dropped (DS5C1 L3764)
  bool change_on_set_point = false;     // 6040h bit 9 honoured (DS1000A-EC L1729-L1738, L2081-L2086)
  bool sin2_profile = false;            // 6086h = 1 selects a sin^2 ramp (DS1000A-EC L1831-L1834)
  bool halt_discards_on_immediate = false;  // halt + bit 5 + new set-point drops the target and holds (DS1000A-EC L2111-L2117)
};

// A live quantity of the drive that a vendor monitor object shows (profile `drive.monitors`).
enum class MonitorQuantity : std::uint8_t {
  MotorSpeedRpm,        // actual motor speed (606Ch as motor r/min)
  SpeedDemandRpm,       // velocity demand (606Bh as motor r/min)
  TorqueDemandPercent,  // 6074h in % of rated torque
  TorqueActualPercent,  // 6077h in % of rated torque
  MotorCurrentA,        // torque-producing motor current, A (signed)
};

// One monitor object the drive writes every control step: raw = quantity / scale, rounded and cut
// to the object's width (DS5C1 U0-00 = 3000h, r/min: scale 1; U0-18 = 3012h, 0.01 A: scale 0.01).
struct MonitorSpec {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  MonitorQuantity quantity = MonitorQuantity::MotorSpeedRpm;
  double scale = 1.0;
};

struct DriveSpec {
  std::uint32_t control_period_ns = 125000;           // internal position/velocity loop period
  bool stepper = false;                               // closed-loop stepper (open/closed-loop modes)
  double stopped_speed_rpm = 30.0;                    // "stopped" for stop sequences
  std::uint32_t mode_switch_ns = 0;                   // time a mode change takes (6061h lags)
  bool mode_switch_while_enabled = true;              // false: 6060h changes only act outside OE
  std::vector<std::pair<std::int8_t, std::int8_t>> forbidden_mode_switches;  // {from, to} in OE
  bool zero_mode_keeps_previous = true;               // writing 6060h = 0 after a mode keeps it
  bool halt_aborts_homing = true;
  bool offsets_honoured = true;                       // 60B0h/60B1h/60B2h added to targets
  double torque_mode_speed_cap_rpm = 0.0;             // speed cap in tq/cst (0 = 6080h only)
  double torque_clamp_permille = 0.0;                 // hard torque clamp (0 = motor peak)
  bool csp_clamps_to_max_speed = false;               // csp step beyond 6080h is clamped (else alarm)
  SoftLimitRule soft_limits = SoftLimitRule::Always;
  PositionRangeRule position_range = PositionRangeRule::Full;
  LimitSwitchRule limit_switches = LimitSwitchRule::QuickStop;
  BrakeRule brake = BrakeRule::Automatic;
  bool torque_off_input = false;                      // TO/STO input forces Switch on disabled
  std::uint32_t servo_on_delay_ns = 0;                // Switched on -> Operation enabled takes this long
  double overspeed_factor = 1.2;                      // overspeed alarm above factor * 6080h (when no vendor level)
  ProfilePositionSpec pp;
  ControlGainSpec gains;
  DriveLevelSpec levels;
  StepperSpec stepper_loop;
  DriveAlarmCauses alarms;
  VendorStopSpec vendor_stop;
  AlarmRulesSpec alarm_rules;
  IoRuleSet io_rules = IoRuleSet::Generic;
  SoftLimitStop soft_limit_stop = SoftLimitStop::AtLimit;
  std::vector<MonitorSpec> monitors;                  // vendor monitor objects kept live (optional key)
};

}  // namespace vdrive::profile
