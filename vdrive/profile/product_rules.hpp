#pragma once
// The behaviours that differ between products but have no column in the CiA 402 data (objects,
// modes, alarm table): each is named in profile.yaml (drive.vendor_stop, drive.alarm_rules,
// drive.io_rules, drive.soft_limit_stop, the homing rule keys) so that a new product is a new
// folder of files, never a new branch in the drive. Format and values: docs/drive.md.
#include <cstdint>
#include <string>
#include <vector>

namespace vdrive::profile {

// One vendor parameter the drive reads as a raw integer; index 0 = the product has none and the
// drive reads `fallback`.
struct ObjectSlot {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::int16_t fallback = 0;
};

// How the vendor's own ("servo-side") stop sequences read their parameters.
enum class VendorStopRule : std::uint8_t {
  None,       // no vendor sequence: option code 0 is CiA 402 "disable drive function" (coast)
  Panasonic,  // even = dynamic brake, odd = free run; 8/9 (servo off) and 4-7 (alarm) immediate stop
  Xinje,      // 0/1 coast, 2/3 decelerate, 4/5 dynamic brake; servo-off alarms always coast
};

struct VendorStopSpec {
  VendorStopRule rule = VendorStopRule::None;
  ObjectSlot servo_off;     // sequence at servo off / option code 0
  ObjectSlot alarm;         // sequence at alarm
  ObjectSlot stop_torque;   // immediate-stop torque, % of rated (0 = the normal torque limit)
  ObjectSlot stop_time_ms;  // time a Decelerate stop takes, ms
};

enum class ErrorRegisterRule : std::uint8_t {
  AlStatusDefined,  // 1001h bit 4: alarm with an AL status code, bit 7: any other
  Cia301Class,      // bit 0 always, plus the class bit of the 603Fh value (CiA 301 1001h)
};

enum class AlarmHistoryKind : std::uint8_t {
  None,              // no alarm history
  DiagnosisHistory,  // 10F3h diagnosis messages, EEPROM-backed
  XinjeMonitors,     // monitor count and recent codes at 3100h + n
};

// How the product reports and clears its alarms, beyond its alarm table.
struct AlarmRulesSpec {
  ErrorRegisterRule error_register = ErrorRegisterRule::Cia301Class;
  bool emergency_sub_code = false;       // EMCY data[0] = the alarm's sub code
  bool emergency_gated_by_10f3 = false;  // EMCY only while 10F3h-05h bit 0 = 1
  AlarmHistoryKind history = AlarmHistoryKind::None;
  // One alarm that becomes clearable only some time after it occurred ("" = none).
  std::string delayed_clear_code;
  std::uint32_t delayed_clear_after_ms = 0;
  // An object whose write of `drive_clear_value` clears the alarms from the drive's own side, as
  // the panel does (DS5C1 F0-00 = 4000h, L7400-L7412); index 0 = none.
  std::uint16_t drive_clear_index = 0;
  std::uint8_t drive_clear_subindex = 0;
  std::uint32_t drive_clear_value = 0;
};

// Which product's 60FDh/60FEh bit layout, input logic and touch-probe quirks the I/O follows.
enum class IoRuleSet : std::uint8_t {
  Generic,  // plain CiA 402 / ETG.6010: 60FDh bits 0-2, probe inputs and index only
  A6B,      // Panasonic MINAS-A6B
  DS5C1,    // Xinje DS5C1 (firmware 3791 and later)
  DS1000A,  // DS1000A-EC closed-loop stepper
};

// How a software limit (607Dh) stops a move that reaches it.
enum class SoftLimitStop : std::uint8_t {
  AtLimit,  // the set-point stops at the limit
  Ramp,     // the move decelerates by 6085h from the limit
};

// What a negative 6098h method does.
enum class HomingVendorMethods : std::uint8_t {
  None,              // no vendor methods
  ManufacturerOnly,  // reserved for the manufacturer, no documented sequence: homing error
  XinjeHardStop,     // push until torque and standstill hold, then index pulses and a fixed move
  TorqueLimit,       // push to the torque limit for the detection time, then optionally the index
};

// A vendor "push against a hard stop" method.
struct HardStopMethod {
  std::int8_t method = 0;
  int direction = +1;               // push direction
  bool push_at_zero_speed = false;  // push at 6099h-02h instead of 6099h-01h
  bool index_after = false;         // then the index pulse(s) in the opposite direction
};

}  // namespace vdrive::profile
