#pragma once
// How a product reports and clears its alarms, where its manual says so. The alarm table itself is
// data (profiles/<id>/alarms.yaml); these are the behaviours around it that the table has no column
// for, named by the profile's drive.alarm_rules and read once when the drive is built.
#include <cstdint>
#include <string_view>

#include "common/clock.hpp"
#include "vdrive/drive/alarms/alarm_code.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

// The enums are the profile's (drive.alarm_rules in profile.yaml, product_rules.hpp).
using ErrorRegisterRule = profile::ErrorRegisterRule;
using HistoryKind = profile::AlarmHistoryKind;

struct AlarmRules {
  ErrorRegisterRule error_register = ErrorRegisterRule::Cia301Class;
  bool emergency_sub_code = false;       // EMCY data[0] = sub code (A6B L4799-L4842)
  bool emergency_gated_by_10f3 = false;  // EMCY only while 10F3h-05h bit 0 = 1 (A6B L4573-L4575)
  HistoryKind history = HistoryKind::None;
  // One alarm that becomes clearable only some time after it occurred; a reset asked for earlier is
  // carried out once it may (A6B Err16.0, 10 s, L32918-L32920). Points into the profile.
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
