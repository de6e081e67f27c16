#include "vdrive/scenario/expectation_check.hpp"

#include <cmath>

#include <fmt/format.h>

namespace vdrive::scenario {
namespace {

std::string value_text(const Expectation& e, std::int64_t v) {
  if (e.probe.kind == Probe::Kind::al_state) {
    switch (v & 0x0F) {
      case 1: return "Init";
      case 2: return "Pre-Op";
      case 3: return "Boot";
      case 4: return "Safe-Op";
      case 8: return "Op";
      default: return fmt::format("0x{:X}", v);
    }
  }
  if (v >= 0 && (e.condition.mask || e.probe.kind == Probe::Kind::al_status_code || e.probe.kind == Probe::Kind::esc_register))
    return fmt::format("0x{:04X}", v);
  return fmt::format("{}", v);
}

std::string when_text(const TimePoint& p) {
  static const char* kNames[] = {"start", "preop", "safeop", "op", "enabled", "fault", "target_reached", "step"};
  std::string base = kNames[static_cast<int>(p.event)];
  if (p.event == EventKind::step) base += " " + p.step;
  if (p.slave) base += fmt::format(" of slave {}", p.slave);
  if (p.event == EventKind::start) return fmt::format("{} ms", static_cast<double>(p.delay) / 1e6);
  return p.delay ? fmt::format("{} ms after {}", static_cast<double>(p.delay) / 1e6, base) : base;
}

}  // namespace

bool holds(const Condition& c, std::int64_t value) {
  const std::int64_t v = c.mask ? (value & *c.mask) : value;
  if (c.equals && v != *c.equals) return false;
  const double d = static_cast<double>(v);
  if (c.min && d < *c.min) return false;
  if (c.max && d > *c.max) return false;
  if (c.near && std::abs(d - *c.near) > c.tolerance) return false;
  return true;
}

std::string describe(const Condition& c) {
  std::string t;
  auto add = [&](const std::string& s) { t += (t.empty() ? "" : " and ") + s; };
  if (c.equals) add(c.mask ? fmt::format("& 0x{:X} == 0x{:X}", *c.mask, *c.equals) : fmt::format("== {}", *c.equals));
  if (c.min) add(fmt::format(">= {}", *c.min));
  if (c.max) add(fmt::format("<= {}", *c.max));
  if (c.near) add(fmt::format("within {} of {}", c.tolerance, *c.near));
  return t;
}

ExpectationCheck::ExpectationCheck(const Expectation& e) : e_(e) {
  r_.name = e.name;
  r_.line = e.line;
}

void ExpectationCheck::decide(bool passed, Nanos now, std::string message) {
  r_.decided = true;
  r_.passed = passed;
  r_.time = now;
  r_.message = std::move(message);
}

void ExpectationCheck::check(Nanos now, std::int64_t value, const EventLog& events) {
  if (r_.decided) return;
  const bool ok = holds(e_.condition, value);
  const std::string seen = value_text(e_, value);
  const double ms = static_cast<double>(now) / 1e6;
  switch (e_.timing) {
    case Expectation::Timing::at: {
      const auto at = events.resolve(e_.when);
      if (!at || now < *at) return;
      decide(ok, now, ok ? fmt::format("{} at {} ms", seen, ms)
                         : fmt::format("{} at {} ms, expected {}", seen, ms, describe(e_.condition)));
      return;
    }
    case Expectation::Timing::by: {
      const auto from = events.resolve(e_.from);
      if (!from || now < *from) return;
      const auto by = events.resolve(e_.when);
      if (by && now > *by) {
        decide(false, now, fmt::format("did not hold by {} ({} ms); last value {}, expected {}", when_text(e_.when),
                                       static_cast<double>(*by) / 1e6, last_ ? value_text(e_, *last_) : seen, describe(e_.condition)));
        return;
      }
      last_ = value;
      ++checks_;
      if (ok) decide(true, now, fmt::format("{} at {} ms", seen, ms));
      return;
    }
    case Expectation::Timing::always: {
      const auto from = events.resolve(e_.from);
      if (!from || now < *from) return;
      if (e_.until) {
        const auto until = events.resolve(*e_.until);
        if (until && now > *until) return;
      }
      ++checks_;
      last_ = value;
      if (!ok) decide(false, now, fmt::format("{} at {} ms, expected {} throughout", seen, ms, describe(e_.condition)));
      return;
    }
  }
}

void ExpectationCheck::finish(Nanos end, const EventLog& events) {
  if (r_.decided) return;
  const double ms = static_cast<double>(end) / 1e6;
  switch (e_.timing) {
    case Expectation::Timing::at: {
      const auto at = events.resolve(e_.when);
      decide(false, end, at ? fmt::format("the run ended at {} ms, before {}", ms, when_text(e_.when))
                            : fmt::format("never checked: {} did not happen", when_text(e_.when)));
      return;
    }
    case Expectation::Timing::by:
      if (!events.resolve(e_.from)) decide(false, end, fmt::format("never checked: {} did not happen", when_text(e_.from)));
      else decide(false, end, fmt::format("did not hold by {} (run ended at {} ms); last value {}, expected {}",
                                          when_text(e_.when), ms, last_ ? value_text(e_, *last_) : "none", describe(e_.condition)));
      return;
    case Expectation::Timing::always:
      if (checks_ == 0) decide(false, end, fmt::format("never checked: {} did not happen", when_text(e_.from)));
      else decide(true, end, fmt::format("held over {} checks", checks_));
      return;
  }
}

}  // namespace vdrive::scenario
