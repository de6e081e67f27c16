#pragma once
// How a product reports and clears its alarms, where its manual says so. The alarm table itself is
// data (profiles/<id>/alarms.yaml); these are the behaviours around it that the table has no column
// for. Unknown products get the CiA 301 / CiA 402 generic rules.
#include <cstdint>
#include <string_view>

#include "common/clock.hpp"
#include "vdrive/drive/alarms/alarm_code.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

enum class ErrorRegisterRule : std::uint8_t {
  AlStatusDefined,  // bit 4: alarm with an AL status code, bit 7: any other (A6B L4767-L4794, DS5C1 L2567-L2581)
  Cia301Class,      // bit 0 always, plus the class bit of the 603Fh value (CiA 301 1001h)
};

enum class HistoryKind : std::uint8_t {
  None,               // no alarm history (DS1000A-EC: none documented, L4309-L4392)
  DiagnosisHistory,   // A6B 10F3h, 14 messages, EEPROM-backed (L8905-L9146)
  XinjeMonitors,      // DS5C1 U1-14 count, U1-16..U1-20 recent codes (3100h + n, L7380, L9072-L9100)
};

struct AlarmRules {
  ErrorRegisterRule error_register = ErrorRegisterRule::Cia301Class;
  bool emergency_sub_code = false;       // EMCY data[0] = sub code (A6B L4799-L4842)
  bool emergency_gated_by_10f3 = false;  // EMCY only while 10F3h-05h bit 0 = 1 (A6B L4573-L4575)
  HistoryKind history = HistoryKind::None;
  // One alarm that becomes clearable only some time after it occurred; a reset asked for earlier is
  // carried out once it may (A6B Err16.0, 10 s, L32918-L32920).
  std::string_view delayed_clear_code;
  Nanos delayed_clear_after = 0;
};

AlarmRules alarm_rules_for(const profile::ProductProfile& profile);

// The EtherCAT communication alarms, whose stop follows 605Eh: A6B Err80.x/81.x/85.x/88.x (L1651-L1653,
// L26465, L27538), DS5C1 E-8xx (L7109-L7139), DS1000A-EC FF80h ESM error (L4386-L4392).
bool is_communication_alarm(const profile::AlarmSpec& alarm);

// 1001h bits contributed by one active alarm.
std::uint8_t error_register_bits(const profile::AlarmSpec& alarm, ErrorRegisterRule rule);

}  // namespace vdrive::drive
