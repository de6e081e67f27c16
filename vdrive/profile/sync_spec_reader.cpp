// profile.yaml `sync`: sync modes, cycle times, 1C32h/1C33h values, shift and watchdog rules.
#include <algorithm>

#include <fmt/format.h>

#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {
namespace {

bool ascending_unique(const std::vector<std::uint32_t>& v) {
  return std::adjacent_find(v.begin(), v.end(), std::greater_equal<>()) == v.end();
}

SyncObjectSpec read_sync_object(YamlMapReader m) {
  SyncObjectSpec o;
  o.default_sync_type = m.u16("default_sync_type");
  o.accepted_sync_types = m.u16_list("accepted_sync_types");
  for (const std::uint16_t t : o.accepted_sync_types)
    if (t != 0x00 && t != 0x01 && t != 0x02 && t != 0x03 && t != 0x22)
      m.fail("accepted_sync_types", fmt::format("0x{:02X} is not an ETG.1020 sync type (0x00-0x03, 0x22)", t));
  if (std::find(o.accepted_sync_types.begin(), o.accepted_sync_types.end(), o.default_sync_type) ==
      o.accepted_sync_types.end())
    m.fail("default_sync_type", "is not one of accepted_sync_types");
  o.default_cycle_time_ns = m.u32("default_cycle_time_ns");
  o.cycle_time_writable = m.boolean("cycle_time_writable");
  o.default_shift_time_ns = m.u32("default_shift_time_ns");
  o.shift_time_writable = m.boolean("shift_time_writable");
  o.supported_sync_types = m.u16("supported_sync_types");
  o.min_cycle_time_ns = m.u32("min_cycle_time_ns");
  o.calc_and_copy_time_ns = m.u32("calc_and_copy_time_ns");
  o.delay_time_ns = m.u32("delay_time_ns");
  o.error_counters = m.boolean("error_counters");
  m.finish();
  return o;
}

ShiftTimeRule read_shift(YamlMapReader m) {
  ShiftTimeRule r;
  r.step_ns = m.u32("step_ns");
  r.max_ns = m.u32("max_ns");
  if (r.step_ns != 0 && r.max_ns % r.step_ns != 0) m.fail("max_ns", "expected a multiple of step_ns");
  r.below_cycle_time = m.boolean("below_cycle_time");
  r.cycle_times_ns = m.u32_list("cycle_times_ns");
  if (!ascending_unique(r.cycle_times_ns)) m.fail("cycle_times_ns", "expected ascending, distinct values");
  m.finish();
  return r;
}

// A 1C32h/1C33h counter subindex: 0 (not counted) or one of the ETG.1020 counters 0Bh-0Eh, which
// the objects must then have as real counters.
std::uint8_t read_counter_subindex(YamlMapReader& m, std::string_view key, const SyncSpec& s) {
  const std::uint8_t sub = m.u8(key);
  if (sub == 0) return sub;
  if (sub < 0x0B || sub > 0x0E) m.fail(key, "expected 0 (not counted) or a counter subindex 0x0B-0x0E");
  if (!s.sm2.error_counters || !s.sm3.error_counters)
    m.fail(key, "names a counter but sm2/sm3 error_counters is false");
  return sub;
}

}  // namespace

SyncSpec read_sync(YamlMapReader m) {
  SyncSpec s;
  const YAML::Node modes = m.sequence("modes");
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const std::string name = modes[i].IsScalar() ? modes[i].Scalar() : std::string();
    bool* flag = name == "free_run"    ? &s.free_run
                 : name == "sm2_event" ? &s.sm2_event
                 : name == "dc_sync0"  ? &s.dc_sync0
                 : name == "dc_sync1"  ? &s.dc_sync1
                                       : nullptr;
    if (!flag || *flag)
      throw_at(m.file(), modes[i].Mark(),
               "sync.modes[" + std::to_string(i) + "]: expected distinct names from free_run, sm2_event, dc_sync0, dc_sync1");
    *flag = true;
  }
  if (!s.free_run && !s.sm2_event && !s.dc_sync0 && !s.dc_sync1) m.fail("modes", "expected at least one sync mode");

  if (m.has("cycle_times_ns") == m.has("cycle_step_ns"))
    m.fail({}, "give either cycle_times_ns (a list) or cycle_step_ns with cycle_min_ns and cycle_max_ns");
  if (m.has("cycle_times_ns")) {
    s.cycle_times_ns = m.u32_list("cycle_times_ns");
    if (s.cycle_times_ns.empty() || s.cycle_times_ns.front() == 0 || !ascending_unique(s.cycle_times_ns))
      m.fail("cycle_times_ns", "expected ascending, distinct, non-zero cycle times");
    s.cycle_min_ns = s.cycle_times_ns.front();
    s.cycle_max_ns = s.cycle_times_ns.back();
  } else {
    s.cycle_step_ns = m.u32("cycle_step_ns");
    s.cycle_min_ns = m.u32("cycle_min_ns");
    s.cycle_max_ns = m.u32("cycle_max_ns");
    if (s.cycle_step_ns == 0) m.fail("cycle_step_ns", "expected a non-zero step");
    if (s.cycle_min_ns == 0 || s.cycle_min_ns % s.cycle_step_ns != 0)
      m.fail("cycle_min_ns", "expected a non-zero multiple of cycle_step_ns");
    if (s.cycle_max_ns < s.cycle_min_ns || s.cycle_max_ns % s.cycle_step_ns != 0)
      m.fail("cycle_max_ns", "expected a multiple of cycle_step_ns, >= cycle_min_ns");
  }
  s.free_run_min_interval_ns = m.u32("free_run_min_interval_ns");
  s.cycle_must_equal_sync0 = m.boolean("cycle_must_equal_sync0");
  s.accepted_dc_activation = m.u8_list("accepted_dc_activation");

  const YAML::Node limits = m.sequence("mode_min_cycle");
  for (std::size_t i = 0; i < limits.size(); ++i) {
    YamlMapReader l = m.element(limits, "mode_min_cycle", i);
    ModeCycleLimit limit;
    limit.mode = l.i8("mode");
    limit.min_cycle_ns = l.u32("min_cycle_ns");
    if (limit.min_cycle_ns < s.cycle_min_ns || limit.min_cycle_ns > s.cycle_max_ns)
      l.fail("min_cycle_ns", "expected a cycle time inside the product's range");
    l.finish();
    s.mode_min_cycle.push_back(limit);
  }

  s.sm2 = read_sync_object(m.map("sm2"));
  s.sm3 = read_sync_object(m.map("sm3"));
  if (s.sm2.min_cycle_time_ns > s.cycle_min_ns)
    m.fail("sm2", fmt::format("min_cycle_time_ns {} is above the shortest accepted cycle {}", s.sm2.min_cycle_time_ns,
                              s.cycle_min_ns));
  s.input_shift = read_shift(m.map("input_shift"));
  s.output_shift = read_shift(m.map("output_shift"));

  YamlMapReader wd = m.map("watchdog");
  s.watchdog.min_cycles = wd.u8("min_cycles");
  s.watchdog.min_free_run_ns = wd.u32("min_free_run_ns");
  wd.finish();

  s.pll_lock_timeout_ns = m.u32("pll_lock_timeout_ns");
  s.missed_sync_threshold = m.u8("missed_sync_threshold");
  s.missed_sync_threshold_object = m.u16("missed_sync_threshold_object");
  if (s.missed_sync_threshold_object != 0 && s.missed_sync_threshold != 0)
    m.fail("missed_sync_threshold", "expected 0: missed_sync_threshold_object holds the threshold");
  s.sync_error_count_object = m.u16("sync_error_count_object");

  s.sync_types_follow_dc_activation = m.boolean("sync_types_follow_dc_activation");
  s.input_sm2_sync_type = m.u16("input_sm2_sync_type");
  if (s.input_sm2_sync_type != 0x01 && s.input_sm2_sync_type != 0x22)
    m.fail("input_sm2_sync_type", "expected 0x01 or 0x22 (the 1C33h-01h value for SM2-synchronous inputs)");
  if (s.sm2_event && std::find(s.sm3.accepted_sync_types.begin(), s.sm3.accepted_sync_types.end(),
                               s.input_sm2_sync_type) == s.sm3.accepted_sync_types.end())
    m.fail("input_sm2_sync_type", "is not one of sm3.accepted_sync_types");
  s.sm_event_missed_subindex = read_counter_subindex(m, "sm_event_missed_subindex", s);
  s.cycle_too_small_subindex = read_counter_subindex(m, "cycle_too_small_subindex", s);
  if (s.sm_event_missed_subindex != 0 && s.sm_event_missed_subindex == s.cycle_too_small_subindex)
    m.fail("cycle_too_small_subindex", "is the same subindex as sm_event_missed_subindex");
  s.sync_error_flag = m.boolean("sync_error_flag");
  m.finish();
  return s;
}

}  // namespace vdrive::profile
