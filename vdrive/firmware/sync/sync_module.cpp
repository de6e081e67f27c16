// Synchronisation firmware module; see sync_module.hpp.
#include "vdrive/firmware/sync/sync_module.hpp"

#include <array>
#include <limits>

#include "ethercat/little_endian.hpp"
#include "vdrive/firmware/pdi.hpp"

namespace vdrive::firmware::sync {
namespace {

constexpr std::uint32_t kSm2Event = 1u << (al_event::kSmShift + 2);
// Free run with 1C32h-02h = 0 ("may be 0", A6B L7790): the drive's own period.
constexpr Nanos kDefaultFreeRunCycle = 1000000;

std::uint64_t read_u64(Pdi& pdi, std::uint16_t address) {
  std::array<std::uint8_t, 8> b{};
  pdi.read(address, b);
  return ecat::get_le64(b.data());
}

}  // namespace

SyncModule::SyncModule(const FirmwareContext& context)
    : context_(context),
      rules_(rules_for(context.profile)),
      objects_(context.objects, rules_) {
  objects_.load_power_on_values();
  tasks_.reserve(4);
}

void SyncModule::power_on(Nanos /*now*/) {
  monitor_.stop();
  decision_ = {};
  objects_.load_power_on_values();
}

void SyncModule::on_cycle(std::function<void(Nanos)> task) { tasks_.push_back(std::move(task)); }

void SyncModule::on_start(std::function<void(SyncMode)> listener) {
  start_listeners_.push_back(std::move(listener));
}

std::uint32_t SyncModule::serviced_events() const { return al_event::kSync0 | kSm2Event; }

void SyncModule::on_events(std::uint32_t events, Nanos now) {
  if (events & al_event::kSync0) {
    // Reading the SYNC0 status acknowledges the event (ET1100), whatever the state.
    context_.pdi.read_u8(reg::kDcSync0Status);
    if (monitor_.running() && decision_.mode == SyncMode::DcSync0) {
      const std::uint32_t cycle = context_.pdi.read_u32(reg::kDcSync0CycleTime);
      const std::uint64_t edge = read_u64(context_.pdi, reg::kDcNextSync0) - cycle;
      // The cycle runs at the pulse, as on a microcontroller whose interrupt is exact: when the
      // host's loop gets to the pulse late, the outputs are dated at the pulse and the drive's
      // set-point segment starts there, not at the moment the loop looked.
      const std::uint64_t system_now = read_u64(context_.pdi, reg::kDcSystemTime);
      Nanos cycle_at = now;
      if (system_now >= edge && system_now - edge < cycle) cycle_at = now - static_cast<Nanos>(system_now - edge);
      handle(monitor_.on_edge(edge, now, cycle), cycle_at);
    }
  }
  if ((events & kSm2Event) && monitor_.running() && decision_.mode == SyncMode::Sm2Event)
    handle(monitor_.on_edge(static_cast<std::uint64_t>(now), now), now);
}

CheckResult SyncModule::check_transition(ecat::AlState from, ecat::AlState to) {
  if (from != ecat::AlState::PreOp || to != ecat::AlState::SafeOp) return CheckResult::pass();
  SyncSettings settings;
  settings.dc_activation = context_.pdi.read_u8(reg::kDcActivation);
  settings.sync0_cycle_ns = context_.pdi.read_u32(reg::kDcSync0CycleTime);
  settings.output_sync_type = static_cast<std::uint16_t>(objects_.get(kOutputSync, sub::kSyncType));
  settings.input_sync_type = static_cast<std::uint16_t>(objects_.get(kInputSync, sub::kSyncType));
  settings.cycle_time_ns = static_cast<std::uint32_t>(objects_.get(kOutputSync, sub::kCycleTime));

  settings = rewrite_from_dc_activation(rules_, settings);
  objects_.set(kOutputSync, sub::kSyncType, settings.output_sync_type);
  objects_.set(kInputSync, sub::kSyncType, settings.input_sync_type);

  decision_ = check_sync_settings(rules_, context_.profile.al_codes, settings);
  if (decision_.result.ok()) publish_running_values(settings);
  return decision_.result;
}

void SyncModule::publish_running_values(const SyncSettings& s) {
  const bool dc = decision_.mode == SyncMode::DcSync0;
  for (const std::uint16_t index : {kOutputSync, kInputSync}) {
    objects_.set(index, sub::kSync0CycleTime, dc ? s.sync0_cycle_ns : 0);
    objects_.set(index, sub::kSyncError, 0);
  }
  // Read-only cycle times show what the drive runs: 1C32h-02h from 09A0h (DS1000A), 1C33h-02h
  // a copy of 1C32h-02h (A6B L8000-L8030).
  if (!rules_.spec.sm2.cycle_time_writable && dc) objects_.set(kOutputSync, sub::kCycleTime, s.sync0_cycle_ns);
  if (!rules_.spec.sm3.cycle_time_writable)
    objects_.set(kInputSync, sub::kCycleTime, objects_.get(kOutputSync, sub::kCycleTime));
}

MonitorConfig SyncModule::monitor_config() const {
  MonitorConfig c;
  c.mode = decision_.mode;
  c.cycle = decision_.cycle_ns;
  if (c.mode == SyncMode::FreeRun && c.cycle == 0) {
    c.cycle = rules_.spec.sm2.min_cycle_time_ns != 0 ? rules_.spec.sm2.min_cycle_time_ns
                                                     : kDefaultFreeRunCycle;
  }
  c.lock_timeout = rules_.spec.pll_lock_timeout_ns;
  c.lock_edges = rules_.lock_edges;
  c.missed_threshold = rules_.spec.missed_sync_threshold_object != 0
                           ? static_cast<int>(objects_.get(rules_.spec.missed_sync_threshold_object, 0) & 0x0F)
                           : rules_.spec.missed_sync_threshold;
  return c;
}

void SyncModule::entered(ecat::AlState from, ecat::AlState to, Nanos now) {
  if (from == ecat::AlState::PreOp && to == ecat::AlState::SafeOp) {
    monitor_.start(monitor_config(), now);
    for (auto& listener : start_listeners_) listener(decision_.mode);
  } else if (rank(to) < rank(ecat::AlState::SafeOp)) {
    monitor_.stop();
  }
}

void SyncModule::tick(Nanos now) { handle(monitor_.on_timer(now), now); }

Nanos SyncModule::next_deadline() const { return monitor_.next_deadline(); }

void SyncModule::run_cycle(Nanos now) {
  ++cycles_;
  for (auto& task : tasks_) task(now);
}

void SyncModule::handle(const MonitorReport& r, Nanos cycle_at) {
  if (r.missed > 0) {
    if (rules_.spec.sm_event_missed_subindex != 0) {
      objects_.count(kOutputSync, rules_.spec.sm_event_missed_subindex, static_cast<std::uint64_t>(r.missed));
      objects_.count(kInputSync, rules_.spec.sm_event_missed_subindex, static_cast<std::uint64_t>(r.missed));
    }
    if (rules_.spec.sync_error_count_object != 0)
      objects_.count(rules_.spec.sync_error_count_object, 0, static_cast<std::uint64_t>(r.missed));
  }
  if (r.cycle_too_small && rules_.spec.cycle_too_small_subindex != 0) {
    objects_.count(kOutputSync, rules_.spec.cycle_too_small_subindex, 1);
    objects_.count(kInputSync, rules_.spec.cycle_too_small_subindex, 1);
  }
  if (r.locked_now) {
    for (const std::uint16_t index : {kOutputSync, kInputSync}) objects_.set(index, sub::kSyncError, 0);
    // A measured SM2 cycle (read-only 1C32h-02h) is what the drive now runs; it must be one the
    // product takes (DS1000A: 1 ms steps, L691-L693).
    if (!rules_.spec.sm2.cycle_time_writable && decision_.mode == SyncMode::Sm2Event) {
      const auto measured = static_cast<std::uint32_t>(monitor_.cycle());
      objects_.set(kOutputSync, sub::kCycleTime, measured);
      objects_.set(kInputSync, sub::kCycleTime, measured);
      if (!cycle_time_accepted(rules_.spec, measured)) {
        monitor_.stop();
        raise_fault(context_.profile.al_codes.invalid_sync_cycle_time, ecat::AlState::PreOp);
        return;
      }
    }
  }
  if (r.run_cycle) run_cycle(cycle_at);

  const profile::AlStatusCodes& codes = context_.profile.al_codes;
  switch (r.fault) {
    case MonitorReport::Fault::None: break;
    case MonitorReport::Fault::NoLock:
      raise_fault(codes.no_sync_error, ecat::AlState::PreOp);
      break;
    case MonitorReport::Fault::LostSync:
      if (rules_.spec.sync_error_flag)
        for (const std::uint16_t index : {kOutputSync, kInputSync}) objects_.set(index, sub::kSyncError, 1);
      raise_fault(codes.sync_error, ecat::AlState::SafeOp);
      break;
    case MonitorReport::Fault::PllError:
      if (decision_.mode == SyncMode::Sm2Event && !rules_.spec.sm2_in_step_check) break;
      if (rules_.spec.sync_error_flag)
        for (const std::uint16_t index : {kOutputSync, kInputSync}) objects_.set(index, sub::kSyncError, 1);
      raise_fault(codes.pll_error, ecat::AlState::SafeOp);
      break;
  }
}

}  // namespace vdrive::firmware::sync
