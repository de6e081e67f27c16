// profile.yaml `drive`: the product's CiA 402 behaviour as data (DriveSpec). Every field is
// required, so each product states each value (with its manual line) instead of inheriting a default.
#include <algorithm>
#include <array>
#include <string_view>

#include <fmt/format.h>

#include "vdrive/profile/enum_reader.hpp"
#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {
namespace {

constexpr std::array<std::pair<std::string_view, SoftLimitRule>, 3> kSoftLimitRules{{
    {"always", SoftLimitRule::Always}, {"after_homing", SoftLimitRule::AfterHoming}, {"ignored", SoftLimitRule::Ignored}}};
constexpr std::array<std::pair<std::string_view, PositionRangeRule>, 2> kPositionRangeRules{{
    {"full", PositionRangeRule::Full}, {"wrap", PositionRangeRule::Wrap}}};
constexpr std::array<std::pair<std::string_view, LimitSwitchRule>, 3> kLimitSwitchRules{{
    {"quick_stop", LimitSwitchRule::QuickStop}, {"alarm", LimitSwitchRule::Alarm},
    {"report_only", LimitSwitchRule::ReportOnly}}};
constexpr std::array<std::pair<std::string_view, BrakeRule>, 2> kBrakeRules{{
    {"automatic", BrakeRule::Automatic}, {"master", BrakeRule::Master}}};
constexpr std::array<std::pair<std::string_view, IoRuleSet>, 4> kIoRuleSets{{
    {"generic", IoRuleSet::Generic}, {"minas_a6b", IoRuleSet::A6B}, {"xinje_ds5c1", IoRuleSet::DS5C1},
    {"ds1000a_ec", IoRuleSet::DS1000A}}};
constexpr std::array<std::pair<std::string_view, SoftLimitStop>, 2> kSoftLimitStops{{
    {"at_limit", SoftLimitStop::AtLimit}, {"ramp", SoftLimitStop::Ramp}}};
constexpr std::array<std::pair<std::string_view, MonitorQuantity>, 5> kMonitorQuantities{{
    {"motor_speed_rpm", MonitorQuantity::MotorSpeedRpm}, {"speed_demand_rpm", MonitorQuantity::SpeedDemandRpm},
    {"torque_demand_percent", MonitorQuantity::TorqueDemandPercent},
    {"torque_actual_percent", MonitorQuantity::TorqueActualPercent}, {"motor_current_a", MonitorQuantity::MotorCurrentA}}};

// A key naming a vendor alarm must name one of alarms.yaml ("" = none).
void require_alarm(const ProductProfile& p, const std::string& file, const std::string& key, const std::string& code) {
  if (!code.empty() && p.find_alarm(code) == nullptr)
    throw ProfileError(file + ": " + key + ": '" + code + "' is not an alarm of alarms.yaml");
}

// {index: 0x3100, subindex: 0, scale: 0.1, fallback: 20.0}; a product without the parameter writes
// {index: 0, fallback: ...} (no subindex or scale: there is nothing to scale).
ParameterRef read_parameter(YamlMapReader& parent, std::string_view key) {
  YamlMapReader m = parent.map(key);
  ParameterRef r;
  r.index = m.u16("index");
  if (r.index == 0) {
    if (m.has("subindex") || m.has("scale")) m.fail("index", "is 0 (no such parameter): give only fallback");
  } else {
    if (r.index < 0x2000) m.fail("index", fmt::format("0x{:04X} is not a vendor or profile object (2000h..FFFFh)", r.index));
    r.subindex = m.u8("subindex");
    r.scale = m.real("scale");
    if (r.scale == 0.0) m.fail("scale", "expected a number > 0");
  }
  r.fallback = m.real("fallback");
  m.finish();
  return r;
}

ControlGainSpec read_gains(YamlMapReader m) {
  ControlGainSpec g;
  g.position_gain = read_parameter(m, "position_gain");
  g.velocity_gain = read_parameter(m, "velocity_gain");
  g.velocity_integral = read_parameter(m, "velocity_integral");
  g.torque_filter = read_parameter(m, "torque_filter");
  g.inertia_ratio = read_parameter(m, "inertia_ratio");
  g.velocity_feedforward = read_parameter(m, "velocity_feedforward");
  if (g.velocity_feedforward.fallback > 1.0) m.fail("velocity_feedforward", "fallback is a fraction, expected 0..1");
  m.finish();
  return g;
}

DriveLevelSpec read_levels(YamlMapReader m) {
  DriveLevelSpec l;
  l.following_error = read_parameter(m, "following_error");
  l.following_error_in_increments = m.boolean("following_error_in_increments");
  l.following_error_in_revolutions = m.boolean("following_error_in_revolutions");
  if (l.following_error_in_increments && l.following_error_in_revolutions)
    m.fail("following_error_in_revolutions", "the level has one unit: increments or revolutions, not both");
  l.overspeed_rpm = read_parameter(m, "overspeed_rpm");
  l.overspeed_reverse_rpm = read_parameter(m, "overspeed_reverse_rpm");
  l.overload = read_parameter(m, "overload");
  l.overload_time_constant_s = m.real("overload_time_constant_s");
  if (l.overload.fallback > 0.0 && !(l.overload_time_constant_s > 0.0))
    m.fail("overload_time_constant_s", "expected a time constant > 0 s when the overload is supervised");
  m.finish();
  return l;
}

StepperSpec read_stepper_loop(YamlMapReader m, bool stepper) {
  StepperSpec s;
  s.loop_mode = read_parameter(m, "loop_mode");
  s.switch_speed_rpm = read_parameter(m, "switch_speed_rpm");
  s.run_current = read_parameter(m, "run_current");
  if (!stepper) {  // a servo has no open/closed-loop settings to name
    const std::pair<std::string_view, const ParameterRef*> refs[] = {
        {"loop_mode", &s.loop_mode}, {"switch_speed_rpm", &s.switch_speed_rpm}, {"run_current", &s.run_current}};
    for (const auto& [key, ref] : refs)
      if (ref->index != 0) m.fail(key, "names a parameter but drive.stepper is false");
  }
  if (s.run_current.fallback > 1.0) m.fail("run_current", "fallback is a fraction of rated current, expected 0..1");
  m.finish();
  return s;
}

DriveAlarmCauses read_alarm_causes(YamlMapReader m) {
  DriveAlarmCauses a;
  a.following_error = m.string("following_error", 16);
  a.overspeed = m.string("overspeed", 16);
  a.overload = m.string("overload", 16);
  a.overtemperature = m.string("overtemperature", 16);
  a.esm_change_while_enabled = m.string("esm_change_while_enabled", 16);
  a.no_mode_at_enable = m.string("no_mode_at_enable", 16);
  a.position_command_jump = m.string("position_command_jump", 16);
  a.position_range = m.string("position_range", 16);
  a.limit_switch = m.string("limit_switch", 16);
  a.both_limit_switches = m.string("both_limit_switches", 16);
  a.homing_error = m.string("homing_error", 16);
  a.encoder_error = m.string("encoder_error", 16);
  a.overvoltage = m.string("overvoltage", 16);
  a.undervoltage = m.string("undervoltage", 16);
  a.main_power_off = m.string("main_power_off", 16);
  a.abort_connection = m.string("abort_connection", 16);
  a.supply_alarms_only_when_enabled = m.boolean("supply_alarms_only_when_enabled");
  m.finish();
  return a;
}

ProfilePositionSpec read_pp(YamlMapReader m) {
  ProfilePositionSpec pp;
  pp.buffered_set_point = m.boolean("buffered_set_point");
  pp.change_on_set_point = m.boolean("change_on_set_point");
  pp.sin2_profile = m.boolean("sin2_profile");
  pp.halt_discards_on_immediate = m.boolean("halt_discards_on_immediate");
  m.finish();
  return pp;
}

// [{from: 1, to: 8}, ...]: mode changes the product refuses while Operation enabled.
std::vector<std::pair<std::int8_t, std::int8_t>> read_forbidden_switches(YamlMapReader& m, const ModesSpec& modes) {
  std::vector<std::pair<std::int8_t, std::int8_t>> out;
  const YAML::Node seq = m.sequence("forbidden_mode_switches");
  const auto supported = [&](std::int8_t x) { return std::find(modes.modes.begin(), modes.modes.end(), x) != modes.modes.end(); };
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader e = m.element(seq, "forbidden_mode_switches", i);
    const std::int8_t from = e.i8("from"), to = e.i8("to");
    if (!supported(from)) e.fail("from", fmt::format("{} is not one of modes.modes", from));
    if (!supported(to)) e.fail("to", fmt::format("{} is not one of modes.modes", to));
    if (from == to) e.fail("to", "equals from");
    e.finish();
    out.emplace_back(from, to);
  }
  return out;
}

// [{index: 0x3000, quantity: motor_speed_rpm, scale: 1}, ...]; optional.
std::vector<MonitorSpec> read_monitors(YamlMapReader& m) {
  std::vector<MonitorSpec> out;
  if (!m.has("monitors")) return out;
  const YAML::Node seq = m.sequence("monitors");
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader e = m.element(seq, "monitors", i);
    MonitorSpec s;
    s.index = e.u16("index");
    if (s.index == 0) e.fail("index", "expected an object index");
    if (e.has("subindex")) s.subindex = e.u8("subindex");
    s.quantity = read_enum(e, "quantity", kMonitorQuantities);
    s.scale = e.real("scale");
    if (!(s.scale > 0.0)) e.fail("scale", "expected a scale > 0 (quantity units per count)");
    e.finish();
    out.push_back(s);
  }
  return out;
}

}  // namespace

DriveSpec read_drive(YamlMapReader m, const ModesSpec& modes) {
  DriveSpec d;
  d.control_period_ns = m.u32("control_period_ns");
  if (d.control_period_ns == 0) m.fail("control_period_ns", "expected a period > 0");
  d.stepper = m.boolean("stepper");
  d.stopped_speed_rpm = m.real("stopped_speed_rpm");
  if (d.stopped_speed_rpm == 0.0) m.fail("stopped_speed_rpm", "expected a speed > 0");
  d.mode_switch_ns = m.u32("mode_switch_ns");
  d.mode_switch_while_enabled = m.boolean("mode_switch_while_enabled");
  d.forbidden_mode_switches = read_forbidden_switches(m, modes);
  if (!d.mode_switch_while_enabled && !d.forbidden_mode_switches.empty())
    m.fail("forbidden_mode_switches", "lists switches but mode_switch_while_enabled is false (none act in OE)");
  d.zero_mode_keeps_previous = m.boolean("zero_mode_keeps_previous");
  d.halt_aborts_homing = m.boolean("halt_aborts_homing");
  d.offsets_honoured = m.boolean("offsets_honoured");
  d.torque_mode_speed_cap_rpm = m.real("torque_mode_speed_cap_rpm");
  d.torque_clamp_permille = m.real("torque_clamp_permille");
  d.csp_clamps_to_max_speed = m.boolean("csp_clamps_to_max_speed");
  d.soft_limits = read_enum(m, "soft_limits", kSoftLimitRules);
  d.soft_limit_stop = read_enum(m, "soft_limit_stop", kSoftLimitStops);
  d.position_range = read_enum(m, "position_range", kPositionRangeRules);
  d.limit_switches = read_enum(m, "limit_switches", kLimitSwitchRules);
  d.brake = read_enum(m, "brake", kBrakeRules);
  d.torque_off_input = m.boolean("torque_off_input");
  d.servo_on_delay_ns = m.u32("servo_on_delay_ns");
  d.overspeed_factor = m.real("overspeed_factor");
  if (d.overspeed_factor < 1.0) m.fail("overspeed_factor", "expected >= 1 (the alarm level is at or above 6080h)");
  d.pp = read_pp(m.map("pp"));
  d.gains = read_gains(m.map("gains"));
  d.levels = read_levels(m.map("levels"));
  d.stepper_loop = read_stepper_loop(m.map("stepper_loop"), d.stepper);
  d.alarms = read_alarm_causes(m.map("alarms"));
  d.vendor_stop = read_vendor_stop(m.map("vendor_stop"));
  d.alarm_rules = read_alarm_rules(m.map("alarm_rules"));
  d.io_rules = read_enum(m, "io_rules", kIoRuleSets);
  d.monitors = read_monitors(m);
  if (d.limit_switches == LimitSwitchRule::Alarm && d.alarms.limit_switch.empty())
    m.fail("limit_switches", "is alarm but alarms.limit_switch names no alarm");
  m.finish();
  return d;
}

void check_drive_alarms(const ProductProfile& p, const std::string& file) {
  const DriveAlarmCauses& a = p.drive.alarms;
  const std::pair<std::string_view, const std::string*> causes[] = {
      {"following_error", &a.following_error},
      {"overspeed", &a.overspeed},
      {"overload", &a.overload},
      {"overtemperature", &a.overtemperature},
      {"esm_change_while_enabled", &a.esm_change_while_enabled},
      {"no_mode_at_enable", &a.no_mode_at_enable},
      {"position_command_jump", &a.position_command_jump},
      {"position_range", &a.position_range},
      {"limit_switch", &a.limit_switch},
      {"both_limit_switches", &a.both_limit_switches},
      {"homing_error", &a.homing_error},
      {"encoder_error", &a.encoder_error},
      {"overvoltage", &a.overvoltage},
      {"undervoltage", &a.undervoltage},
      {"main_power_off", &a.main_power_off},
      {"abort_connection", &a.abort_connection},
  };
  for (const auto& [name, code] : causes) require_alarm(p, file, "drive.alarms." + std::string(name), *code);
  require_alarm(p, file, "drive.alarm_rules.delayed_clear.code", p.drive.alarm_rules.delayed_clear_code);
  require_alarm(p, file, "homing.cancel_after_detection_alarm", p.homing.cancel_after_detection_alarm);
}

}  // namespace vdrive::profile
