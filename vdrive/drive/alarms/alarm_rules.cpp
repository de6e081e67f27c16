#include "vdrive/drive/alarms/alarm_rules.hpp"

namespace vdrive::drive {

bool is_communication_alarm(const profile::AlarmSpec& alarm) {
  const AlarmCode code = parse_alarm_code(alarm.code);
  switch (code.style) {
    case AlarmCode::Style::Panasonic:
      return code.main == 80 || code.main == 81 || code.main == 85 || code.main == 88;
    case AlarmCode::Style::Xinje: return code.main >= 80 && code.main <= 89;
    case AlarmCode::Style::Cia402: return alarm.error_code == 0xFF80;
    case AlarmCode::Style::Unknown: break;
  }
  return false;
}

std::uint8_t error_register_bits(const profile::AlarmSpec& alarm, ErrorRegisterRule rule) {
  if (alarm.warning) return 0;  // "warnings are not shown" (A6B L4763, DS5C1 L2566)
  if (rule == ErrorRegisterRule::AlStatusDefined) return alarm.al_status_code != 0 ? 0x10 : 0x80;
  // CiA 301: bit 0 generic (any error), 1 current (2xxxh), 2 voltage (3xxxh), 3 temperature (4xxxh),
  // 4 communication (81xxh; CiA 402 names 7500h "communication"), 7 manufacturer specific (FFxxh).
  const std::uint16_t ec = alarm.error_code;
  std::uint8_t bits = 0x01;
  switch (ec >> 12) {
    case 0x2: bits |= 0x02; break;
    case 0x3: bits |= 0x04; break;
    case 0x4: bits |= 0x08; break;
    default: break;
  }
  if ((ec & 0xFF00) == 0x8100 || (ec & 0xFF00) == 0x7500) bits |= 0x10;
  if ((ec & 0xFF00) == 0xFF00) bits |= 0x80;
  return bits;
}

}  // namespace vdrive::drive
