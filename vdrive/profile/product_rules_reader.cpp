// profile.yaml drive.vendor_stop, drive.alarm_rules and the homing rule keys: the product rules the
// CiA 402 data has no column for (product_rules.hpp). Like the rest of `drive`, every key is required.
#include <algorithm>
#include <array>
#include <string_view>

#include <fmt/format.h>

#include "vdrive/profile/enum_reader.hpp"
#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {
namespace {

constexpr std::array<std::pair<std::string_view, VendorStopRule>, 3> kVendorStopRules{{
    {"none", VendorStopRule::None}, {"panasonic", VendorStopRule::Panasonic}, {"xinje", VendorStopRule::Xinje}}};
constexpr std::array<std::pair<std::string_view, ErrorRegisterRule>, 2> kErrorRegisterRules{{
    {"al_status_defined", ErrorRegisterRule::AlStatusDefined}, {"cia301_class", ErrorRegisterRule::Cia301Class}}};
constexpr std::array<std::pair<std::string_view, AlarmHistoryKind>, 3> kHistoryKinds{{
    {"none", AlarmHistoryKind::None}, {"diagnosis_history", AlarmHistoryKind::DiagnosisHistory},
    {"xinje_monitors", AlarmHistoryKind::XinjeMonitors}}};
constexpr std::array<std::pair<std::string_view, HomingVendorMethods>, 4> kHomingVendorMethods{{
    {"none", HomingVendorMethods::None}, {"manufacturer_only", HomingVendorMethods::ManufacturerOnly},
    {"xinje_hard_stop", HomingVendorMethods::XinjeHardStop}, {"torque_limit", HomingVendorMethods::TorqueLimit}}};
constexpr std::array<std::pair<std::string_view, int>, 2> kDirections{{{"positive", +1}, {"negative", -1}}};

// {index: 0x3506, subindex: 0, fallback: 0}; a product without the parameter writes {index: 0, fallback: 0}.
ObjectSlot read_slot(YamlMapReader& parent, std::string_view key) {
  YamlMapReader m = parent.map(key);
  ObjectSlot s;
  s.index = m.u16("index");
  if (s.index == 0) {
    if (m.has("subindex")) m.fail("index", "is 0 (no such parameter): give only fallback");
  } else {
    if (s.index < 0x2000) m.fail("index", fmt::format("0x{:04X} is not a vendor or profile object (2000h..FFFFh)", s.index));
    s.subindex = m.u8("subindex");
  }
  s.fallback = m.i16("fallback");
  m.finish();
  return s;
}

}  // namespace

VendorStopSpec read_vendor_stop(YamlMapReader m) {
  VendorStopSpec v;
  v.rule = read_enum(m, "rule", kVendorStopRules);
  v.servo_off = read_slot(m, "servo_off");
  v.alarm = read_slot(m, "alarm");
  v.stop_torque = read_slot(m, "stop_torque");
  v.stop_time_ms = read_slot(m, "stop_time_ms");
  const std::pair<std::string_view, const ObjectSlot*> slots[] = {
      {"servo_off", &v.servo_off}, {"alarm", &v.alarm}, {"stop_torque", &v.stop_torque}, {"stop_time_ms", &v.stop_time_ms}};
  if (v.rule == VendorStopRule::None) {
    for (const auto& [key, slot] : slots)
      if (slot->index != 0) m.fail(key, "names a parameter but rule is none (no vendor stop reads it)");
  } else {
    // The sequences are what the rule reads; without them it would read fallbacks forever.
    if (v.servo_off.index == 0) m.fail("servo_off", "is needed by a vendor stop rule (index 0 given)");
    if (v.alarm.index == 0) m.fail("alarm", "is needed by a vendor stop rule (index 0 given)");
  }
  m.finish();
  return v;
}

AlarmRulesSpec read_alarm_rules(YamlMapReader m) {
  AlarmRulesSpec r;
  r.error_register = read_enum(m, "error_register", kErrorRegisterRules);
  r.emergency_sub_code = m.boolean("emergency_sub_code");
  r.history = read_enum(m, "history", kHistoryKinds);
  r.emergency_gated_by_10f3 = m.boolean("emergency_gated_by_10f3");
  if (r.emergency_gated_by_10f3 && r.history != AlarmHistoryKind::DiagnosisHistory)
    m.fail("emergency_gated_by_10f3", "needs history: diagnosis_history (10F3h holds the gate)");
  YamlMapReader d = m.map("delayed_clear");
  r.delayed_clear_code = d.string("code", 16);
  r.delayed_clear_after_ms = d.u32("after_ms");
  if (r.delayed_clear_code.empty() != (r.delayed_clear_after_ms == 0))
    d.fail("after_ms", "expected > 0 with an alarm code, 0 with code \"\"");
  d.finish();
  if (m.has("drive_clear")) {   // optional: only a product whose panel clear is an object has it
    YamlMapReader c = m.map("drive_clear");
    r.drive_clear_index = c.u16("index");
    r.drive_clear_subindex = c.u8("subindex");
    r.drive_clear_value = c.u32("value");
    if (r.drive_clear_index == 0) c.fail("index", "expected the object's index (leave drive_clear out for none)");
    c.finish();
  }
  m.finish();
  return r;
}

void read_homing_rules(YamlMapReader& m, HomingSpec& h) {
  h.vendor_methods = read_enum(m, "vendor_methods", kHomingVendorMethods);
  const YAML::Node seq = m.sequence("hard_stops");
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader e = m.element(seq, "hard_stops", i);
    HardStopMethod row;
    row.method = e.i8("method");
    if (row.method >= 0) e.fail("method", "expected a vendor method (< 0)");
    if (std::find(h.methods.begin(), h.methods.end(), row.method) == h.methods.end())
      e.fail("method", fmt::format("{} is not one of methods", row.method));
    for (const HardStopMethod& other : h.hard_stops)
      if (other.method == row.method) e.fail("method", fmt::format("{} is listed twice", row.method));
    row.direction = read_enum(e, "direction", kDirections);
    row.push_at_zero_speed = e.boolean("push_at_zero_speed");
    row.index_after = e.boolean("index_after");
    e.finish();
    h.hard_stops.push_back(row);
  }
  const bool pushes = h.vendor_methods == HomingVendorMethods::XinjeHardStop ||
                      h.vendor_methods == HomingVendorMethods::TorqueLimit;
  if (pushes && h.hard_stops.empty()) m.fail("hard_stops", "is empty but vendor_methods pushes against a hard stop");
  if (!pushes && !h.hard_stops.empty())
    m.fail("hard_stops", "lists methods but vendor_methods is not xinje_hard_stop or torque_limit");
  h.offset_only_for_current_position = m.boolean("offset_only_for_current_position");
  h.abrupt_sensor_stop = m.boolean("abrupt_sensor_stop");
  h.index_methods_use_switch_speed = m.boolean("index_methods_use_switch_speed");
  h.cancel_after_detection_alarm = m.string("cancel_after_detection_alarm", 16);
}

}  // namespace vdrive::profile
