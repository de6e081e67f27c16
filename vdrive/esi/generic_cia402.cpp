#include "vdrive/esi/generic_cia402.hpp"

#include <algorithm>

namespace vdrive::esi {
namespace {

using profile::AlarmReaction;
using profile::AlarmSpec;

// CiA 402 modes of operation by their 6502h bit (bit 0 pp ... bit 9 cst), those the drive engine runs.
struct ModeBit {
  unsigned bit;
  std::int8_t mode;
};
constexpr ModeBit kModeBits[] = {{0, 1}, {2, 3}, {3, 4}, {5, 6}, {6, 7}, {7, 8}, {8, 9}, {9, 10}};
// 6502h when the dictionary has none: pp, pv, tq, hm, csp, csv, cst (ETG.6010's usual set).
constexpr std::uint32_t kUsualModes = 0x000003AD;

// The CiA 402 / CiA 301 emergency error codes for what the engine detects; the code is the alarm's
// name, as drives without a display show it.
AlarmSpec alarm(const char* code, const char* name, std::uint16_t error_code, AlarmReaction reaction) {
  AlarmSpec a;
  a.code = code;
  a.name = name;
  a.name_en = name;
  a.error_code = error_code;
  a.emergency_code = error_code;
  a.reaction = reaction;
  a.source = "CiA 402 / CiA 301 error code";
  return a;
}

}  // namespace

const od::ObjectDesc* find_object(const std::vector<od::ObjectDesc>& objects, std::uint16_t index) {
  const auto it = std::lower_bound(objects.begin(), objects.end(), index,
                                   [](const od::ObjectDesc& o, std::uint16_t i) { return o.index < i; });
  return it != objects.end() && it->index == index ? &*it : nullptr;
}

const od::EntryDesc* find_entry(const std::vector<od::ObjectDesc>& objects, std::uint16_t index, std::uint8_t subindex) {
  const od::ObjectDesc* o = find_object(objects, index);
  return o != nullptr ? o->entry(subindex) : nullptr;
}

std::uint64_t default_of(const std::vector<od::ObjectDesc>& objects, std::uint16_t index, std::uint8_t subindex,
                         std::uint64_t otherwise) {
  const od::EntryDesc* e = find_entry(objects, index, subindex);
  if (e == nullptr || e->default_value.empty()) return otherwise;
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(8, e->default_value.size()); ++i)
    v |= static_cast<std::uint64_t>(e->default_value[i]) << (8 * i);
  return v;
}

bool is_cia402_drive(std::uint32_t profile_no, const std::vector<od::ObjectDesc>& objects) {
  return profile_no == 402 && find_entry(objects, 0x6040, 0) != nullptr && find_entry(objects, 0x6041, 0) != nullptr;
}

void apply_generic_cia402(profile::ProductProfile& p, const std::vector<od::ObjectDesc>& objects) {
  // Modes: 6502h's default where it has one, else the usual set; 6060h's power-up value.
  const std::uint32_t supported = static_cast<std::uint32_t>(default_of(objects, 0x6502, 0, 0));
  const std::uint32_t modes = supported != 0 ? supported : kUsualModes;
  p.modes.supported_drive_modes = modes;
  p.modes.modes.clear();
  for (const ModeBit& m : kModeBits)
    if (modes & (1u << m.bit)) p.modes.modes.push_back(m.mode);
  p.modes.default_mode = static_cast<std::int8_t>(default_of(objects, 0x6060, 0, 0));

  // Homing: the CiA 402 methods (1-14, 17-30, 33-35, 37) within 6098h's range, when it exists.
  p.homing = {};
  if (const od::EntryDesc* method = find_entry(objects, 0x6098, 0)) {
    for (int m = 1; m <= 37; ++m) {
      if ((m >= 15 && m <= 16) || (m >= 31 && m <= 32) || m == 36) continue;
      if ((method->min && m < *method->min) || (method->max && m > *method->max)) continue;
      p.homing.methods.push_back(static_cast<std::int8_t>(m));
    }
    p.homing.listed = p.homing.methods;
    p.homing.default_method = static_cast<std::int8_t>(default_of(objects, 0x6098, 0, 0));
  }

  // Touch probe: two channels on 60B8h, rising and falling edges, external input or index pulse.
  p.touch_probe = {};
  if (find_entry(objects, 0x60B8, 0) != nullptr) {
    p.touch_probe.channels = 2;
    p.touch_probe.rising_edge = p.touch_probe.falling_edge = true;
    p.touch_probe.both_edges_at_once = true;
    p.touch_probe.continuous = true;
    p.touch_probe.sources = {{1, 0, 0, "Touch probe input 1"}, {1, 1, 0, "Index pulse"},
                             {2, 0, 0, "Touch probe input 2"}, {2, 1, 0, "Index pulse"}};
  }

  // The drive: CiA 402 defaults. Gains as a well-tuned medium servo; the following-error alarm at
  // 6065h (following error window), overspeed at 1.2 x 6080h.
  profile::DriveSpec d;
  d.control_period_ns = 125000;
  d.gains.position_gain = {0, 0, 1.0, 62.8};
  d.gains.velocity_gain = {0, 0, 1.0, 40.0};
  d.gains.velocity_integral = {0, 0, 1.0, 0.0159};
  d.gains.torque_filter = {0, 0, 1.0, 0.0003};
  d.gains.inertia_ratio = {0, 0, 1.0, 1.0};
  d.gains.velocity_feedforward = {0, 0, 1.0, 0.0};
  d.levels.following_error = {0x6065, 0, 1.0, 2147483647.0};
  d.alarms.following_error = "8611h";
  d.alarms.overspeed = "8400h";
  d.alarms.overtemperature = "4210h";
  d.alarms.encoder_error = "7300h";
  d.alarms.overvoltage = "3210h";
  d.alarms.undervoltage = "3220h";
  d.alarms.position_command_jump = "8611h";
  // A dictionary with 10F3h (ETG.1020 diagnosis history) gets the history kept there.
  if (find_entry(objects, 0x10F3, 0) != nullptr) d.alarm_rules.history = profile::AlarmHistoryKind::DiagnosisHistory;
  p.drive = d;
  p.alarms = {
      alarm("8611h", "Following error", 0x8611, AlarmReaction::Deceleration),
      alarm("8400h", "Velocity speed control (overspeed)", 0x8400, AlarmReaction::ImmediateStop),
      alarm("4210h", "Excess temperature device", 0x4210, AlarmReaction::FreeRun),
      alarm("7300h", "Sensor (encoder)", 0x7300, AlarmReaction::FreeRun),
      alarm("3210h", "DC link over-voltage", 0x3210, AlarmReaction::FreeRun),
      alarm("3220h", "DC link under-voltage", 0x3220, AlarmReaction::FreeRun),
  };
  // One motor: 400 W, 3000 r/min; the encoder resolution from 608Fh-01h where the file gives it.
  profile::MotorSpec motor;
  motor.model = "generic servo motor (400 W)";
  motor.source = "not from a manual: a typical 400 W servo motor";
  motor.rated_power_w = 400;
  motor.rated_torque_nm = 1.27;
  motor.peak_torque_nm = 3.8;
  motor.rated_speed_rpm = 3000;
  motor.max_speed_rpm = 6000;
  motor.encoder_counts_per_rev = static_cast<std::uint32_t>(default_of(objects, 0x608F, 1, 0));
  if (motor.encoder_counts_per_rev == 0) motor.encoder_counts_per_rev = 1u << 17;
  p.motors = {motor};
}

}  // namespace vdrive::esi
