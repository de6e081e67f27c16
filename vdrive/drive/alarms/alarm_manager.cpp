#include "vdrive/drive/alarms/alarm_manager.hpp"

#include <utility>

#include "vdrive/drive/alarms/alarm_code.hpp"

namespace vdrive::drive {

using profile::AlarmSpec;

AlarmManager::AlarmManager(const DriveContext& ctx, EmergencySink sink)
    : ctx_(ctx), sink_(std::move(sink)), rules_(ctx.profile.drive.alarm_rules),
      history_(make_alarm_history(rules_.history, ctx.objects)), error_code_(ctx.objects, 0x603F),
      error_register_ref_(ctx.objects, 0x1001), states_(ctx.profile.alarms.size()) {}

void AlarmManager::power_on() {
  for (State& s : states_) s = State{};
  reset_pending_ = false;
  refresh();
  publish();
  if (history_) history_->power_on();
}

const AlarmManager::State* AlarmManager::state_of(const AlarmSpec& alarm) const {
  const auto& table = ctx_.profile.alarms;
  if (table.empty()) return nullptr;
  // An alarm of this product's table is an element of profile.alarms; anything else is refused.
  const auto* first = table.data();
  if (&alarm < first || &alarm >= first + table.size()) return nullptr;
  return &states_[static_cast<std::size_t>(&alarm - first)];
}

AlarmManager::State* AlarmManager::state_of(const AlarmSpec& alarm) {
  return const_cast<State*>(std::as_const(*this).state_of(alarm));
}

bool AlarmManager::is_active(const AlarmSpec& alarm) const {
  const State* s = state_of(alarm);
  return s && s->active;
}

bool AlarmManager::raise(const AlarmSpec& alarm, Nanos now) { return raise_with(alarm, now, nullptr); }

bool AlarmManager::raise(const AlarmSpec& alarm, Nanos now, const std::array<std::uint8_t, 5>& data) {
  return raise_with(alarm, now, &data);
}

bool AlarmManager::raise_with(const AlarmSpec& alarm, Nanos now, const std::array<std::uint8_t, 5>* data) {
  State* s = state_of(alarm);
  if (!s || s->active) return false;
  s->active = true;
  s->since = now;
  s->order = next_order_++;
  refresh();
  publish();
  if (alarm.warning) return true;   // no emergency (A6B L4561), no history (L8935)
  if (history_ && alarm.history) history_->record(alarm);

  ecat::coe::Emergency e;
  e.error_code = alarm.emergency_code;
  e.error_register = error_register_;   // = 1001h (L4733-L4735)
  if (data) {
    e.data = *data;
  } else if (rules_.emergency_sub_code) {
    e.data[0] = parse_alarm_code(alarm.code).sub;   // L4799-L4842
  }
  emit(e);
  return true;
}

void AlarmManager::set_cause(const AlarmSpec& alarm, bool present) {
  State* s = state_of(alarm);
  if (!s) return;
  s->cause = present;
  if (!present && alarm.warning && s->active) {
    s->active = false;
    refresh();
    publish();
  }
}

std::uint16_t AlarmManager::error_code() const {
  // An alarm wins over a warning (A6B L4703, L33976).
  if (newest_) return newest_->error_code;
  return newest_warning_ ? newest_warning_->error_code : 0;
}

AlarmManager::Block AlarmManager::blocked(bool al_error_pending, bool fault_reaction_active, Nanos now) const {
  if (fault_reaction_active) return Block::Other;   // L34060
  if (active_count_ == 0) return Block::None;       // called every control step: skip the table scan
  bool too_young = false;
  const auto& table = ctx_.profile.alarms;
  for (std::size_t i = 0; i < states_.size(); ++i) {
    const State& s = states_[i];
    if (!s.active || table[i].warning) continue;
    if (s.cause) return Block::Other;                                   // L34048-L34050
    if (al_error_pending && table[i].al_status_code != 0) return Block::Other;   // L34013-L34017
    if (!rules_.delayed_clear_code.empty() && table[i].code == rules_.delayed_clear_code &&
        now - s.since < static_cast<Nanos>(rules_.delayed_clear_after_ms) * 1'000'000)
      too_young = true;                                                 // L32918-L32920
  }
  return too_young ? Block::TooYoung : Block::None;
}

bool AlarmManager::reset_allowed(bool al_error_pending, bool fault_reaction_active, Nanos now) const {
  if (blocked(al_error_pending, fault_reaction_active, now) != Block::None) return false;
  if (active_count_ == 0) return true;
  const auto& table = ctx_.profile.alarms;
  for (std::size_t i = 0; i < states_.size(); ++i)
    if (states_[i].active && !table[i].warning && !table[i].clearable) return false;   // power cycle
  return true;
}

bool AlarmManager::reset(bool al_error_pending, Nanos now) {
  switch (blocked(al_error_pending, false, now)) {
    case Block::TooYoung: reset_pending_ = true; return false;
    case Block::Other: return !active();
    case Block::None: break;
  }
  return clear_clearable();
}

bool AlarmManager::complete_pending_reset(bool al_error_pending, bool fault_reaction_active, Nanos now) {
  if (!reset_pending_ || blocked(al_error_pending, fault_reaction_active, now) != Block::None) return false;
  return clear_clearable();
}

bool AlarmManager::clear_from_drive(bool fault_reaction_active, Nanos now) {
  switch (blocked(false, fault_reaction_active, now)) {
    case Block::TooYoung: reset_pending_ = true; return false;
    case Block::Other: return !active();
    case Block::None: break;
  }
  return clear_clearable();
}

bool AlarmManager::clear_clearable() {
  reset_pending_ = false;
  const auto& table = ctx_.profile.alarms;
  bool cleared = false;
  for (std::size_t i = 0; i < states_.size(); ++i) {
    State& s = states_[i];
    if (s.active && table[i].clearable) {
      s.active = false;
      cleared = true;
    }
  }
  if (!cleared) return !active();
  refresh();
  publish();
  if (!active()) emit(ecat::coe::Emergency{});   // all zero: alarm cleared (L4848-L4885)
  return !active();
}

void AlarmManager::refresh() {
  active_count_ = warning_count_ = 0;
  newest_ = newest_warning_ = nullptr;
  error_register_ = 0;
  std::uint64_t newest_order = 0, newest_warning_order = 0;
  const auto& table = ctx_.profile.alarms;
  for (std::size_t i = 0; i < states_.size(); ++i) {
    const State& s = states_[i];
    if (!s.active) continue;
    const AlarmSpec& a = table[i];
    if (a.warning) {
      ++warning_count_;
      if (s.order > newest_warning_order) newest_warning_order = s.order, newest_warning_ = &a;
      continue;
    }
    ++active_count_;
    // 1001h shows the kinds of every alarm present (L4759).
    error_register_ = static_cast<std::uint8_t>(error_register_ | error_register_bits(a, rules_.error_register));
    if (s.order > newest_order) newest_order = s.order, newest_ = &a;
  }
}

void AlarmManager::publish() {
  error_code_.set(error_code());
  error_register_ref_.set(error_register_);
  if (history_) history_->current(newest_, newest_warning_);   // DS5C1 U1-00/U1-01 (L7380, L9072-L9073)
}

void AlarmManager::emit(const ecat::coe::Emergency& e) const {
  if (!sink_) return;
  if (rules_.emergency_gated_by_10f3 && history_ && !history_->emergency_enabled()) return;   // L4573
  sink_(e);
}

int AlarmManager::newest_index() const {
  return newest_ == nullptr ? -1 : static_cast<int>(newest_ - ctx_.profile.alarms.data());
}

}  // namespace vdrive::drive
