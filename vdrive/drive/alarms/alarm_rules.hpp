#pragma once
// How a product reports and clears its alarms, where its manual says so. The alarm table itself is
// data (profiles/<id>/alarms.yaml); the behaviours around it that the table has no column for are
// the profile's drive.alarm_rules (profile::AlarmRulesSpec), which the alarm manager reads.
#include <cstdint>

#include "vdrive/drive/alarms/alarm_code.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

// The enums are the profile's (drive.alarm_rules in profile.yaml, product_rules.hpp).
using ErrorRegisterRule = profile::ErrorRegisterRule;
using HistoryKind = profile::AlarmHistoryKind;

// The EtherCAT communication alarms, whose stop follows 605Eh: A6B Err80.x/81.x/85.x/88.x (L1651-L1653,
// L26465, L27538), DS5C1 E-8xx (L7109-L7139), DS1000A-EC FF80h ESM error (L4386-L4392).
bool is_communication_alarm(const profile::AlarmSpec& alarm);

// 1001h bits contributed by one active alarm.
std::uint8_t error_register_bits(const profile::AlarmSpec& alarm, ErrorRegisterRule rule);

}  // namespace vdrive::drive
