#include "vdrive/scenario/event_log.hpp"

namespace vdrive::scenario {

EventLog::EventLog(std::size_t slaves) : slaves_(slaves) {}

void EventLog::all_in_state(AlTarget state, Nanos now) {
  std::optional<Nanos>* e = state == AlTarget::preop ? &preop_ : state == AlTarget::safeop ? &safeop_ : state == AlTarget::op ? &op_ : nullptr;
  if (e && !*e) *e = now;
}

void EventLog::statusword(int slave, std::uint16_t s, Nanos now) {
  if (slave < 1 || static_cast<std::size_t>(slave) > slaves_.size()) return;
  Slave& d = slaves_[static_cast<std::size_t>(slave - 1)];
  const std::uint16_t before = d.seen ? d.last : 0;
  if (!d.enabled && (s & 0x006F) == 0x0027) d.enabled = now;
  if (!d.fault && (s & 0x0008) && !(before & 0x0008)) d.fault = now;
  if (d.armed && (s & 0x0400) && !(before & 0x0400) && (s & 0x006F) == 0x0027) {
    d.target_reached = now;
    d.armed = false;
  }
  d.last = s;
  d.seen = true;
}

void EventLog::set_point_given(int slave) {
  if (slave < 1 || static_cast<std::size_t>(slave) > slaves_.size()) return;
  Slave& d = slaves_[static_cast<std::size_t>(slave - 1)];
  d.armed = true;
  d.target_reached.reset();
  // Bit 10 may still be up from the previous target: only a new rising edge counts.
}

void EventLog::step_ran(const std::string& name, Nanos now) {
  if (!name.empty()) steps_.emplace(name, now);
}

std::optional<Nanos> EventLog::resolve(const TimePoint& p) const {
  std::optional<Nanos> base;
  auto slave = [&]() -> const Slave* {
    if (p.slave < 1 || static_cast<std::size_t>(p.slave) > slaves_.size()) return nullptr;
    return &slaves_[static_cast<std::size_t>(p.slave - 1)];
  };
  switch (p.event) {
    case EventKind::start: base = 0; break;
    case EventKind::preop: base = preop_; break;
    case EventKind::safeop: base = safeop_; break;
    case EventKind::op: base = op_; break;
    case EventKind::enabled: if (const Slave* s = slave()) base = s->enabled; break;
    case EventKind::fault: if (const Slave* s = slave()) base = s->fault; break;
    case EventKind::target_reached: if (const Slave* s = slave()) base = s->target_reached; break;
    case EventKind::step: {
      const auto it = steps_.find(p.step);
      if (it != steps_.end()) base = it->second;
      break;
    }
  }
  if (!base) return std::nullopt;
  return *base + p.delay;
}

}  // namespace vdrive::scenario
