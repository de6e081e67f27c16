#include "vdrive/scenario/scenario_loader.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <span>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "ethercat/slave_ref.hpp"
#include "plant/plant_yaml.hpp"
#include "vdrive/drive/product_plant.hpp"
#include "vdrive/fault/fault_fields.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/machine/network_file.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "common/nearest_word.hpp"
#include "common/time_text.hpp"

namespace vdrive::scenario {
namespace {

namespace fs = std::filesystem;

// One YAML mapping read strictly: every key read by name, unknown keys refused by finish().
class Map {
public:
  Map(const YAML::Node& node, const std::string& file, std::string path) : node_(node), file_(file), path_(std::move(path)) {
    if (!node_.IsMap()) fail_at(node_, path_, "expected a mapping");
  }

  bool has(std::string_view key) const {
    asked_.insert(std::string(key));
    return static_cast<bool>(node_[std::string(key)]);
  }

  YAML::Node get(std::string_view key) {
    asked_.insert(std::string(key));
    const YAML::Node v = node_[std::string(key)];
    if (!v) {
      const std::string_view wanted[] = {key};
      misspelt(wanted);  // "duraton:" is reported as itself, not as a missing "duration"
      fail_at(node_, path_, fmt::format("missing \"{}\"", key));
    }
    used_.insert(std::string(key));
    return v;
  }

  // A key of this mapping that nothing asked for and that is a near miss of one of `candidates`
  // fails as a misspelling of it.
  void misspelt(std::span<const std::string_view> candidates) const {
    for (const auto& kv : node_) {
      const std::string k = kv.first.Scalar();
      if (asked_.count(k)) continue;
      // Short keys ("at", "by", "id") are a letter or two apart from each other: one edit only.
      if (const auto best = nearest_word(k, candidates, k.size() <= 3 ? 1 : 2))
        fail_at(kv.first, field(k), fmt::format("unknown key \"{}\", did you mean \"{}\"?", k, *best));
    }
  }

  std::string field(std::string_view key) const { return path_.empty() ? std::string(key) : path_ + "." + std::string(key); }

  std::string string(std::string_view key) {
    const YAML::Node v = get(key);
    if (!v.IsScalar()) fail_at(v, field(key), "expected text");
    return v.Scalar();
  }
  std::string string_or(std::string_view key, std::string fallback) { return has(key) ? string(key) : fallback; }

  std::int64_t integer(std::string_view key, std::int64_t min, std::int64_t max) {
    const YAML::Node v = get(key);
    return integer_of(v, field(key), min, max);
  }
  std::int64_t integer_or(std::string_view key, std::int64_t min, std::int64_t max, std::int64_t fallback) {
    return has(key) ? integer(key, min, max) : fallback;
  }

  double real(std::string_view key) {
    const YAML::Node v = get(key);
    double d = 0.0;
    if (!v.IsScalar() || !YAML::convert<double>::decode(v, d) || !std::isfinite(d))
      fail_at(v, field(key), fmt::format("expected a number, got \"{}\"", v.IsScalar() ? v.Scalar() : "(not a value)"));
    return d;
  }
  double real_or(std::string_view key, double fallback) { return has(key) ? real(key) : fallback; }

  bool boolean(std::string_view key) {
    const YAML::Node v = get(key);
    bool b = false;
    if (!v.IsScalar() || !YAML::convert<bool>::decode(v, b)) fail_at(v, field(key), "expected true or false");
    return b;
  }

  Nanos time(std::string_view key) {
    const YAML::Node v = get(key);
    const auto t = v.IsScalar() ? parse_time(v.Scalar()) : std::nullopt;
    if (!t) fail_at(v, field(key), fmt::format("expected a time with a unit (e.g. 250ms, 1.5s, 125us), got \"{}\"",
                                               v.IsScalar() ? v.Scalar() : "(not a value)"));
    return *t;
  }
  Nanos time_or(std::string_view key, Nanos fallback) { return has(key) ? time(key) : fallback; }

  Map map(std::string_view key) {
    const YAML::Node v = get(key);
    return Map(v, file_, field(key));
  }
  YAML::Node sequence(std::string_view key) {
    const YAML::Node v = get(key);
    if (!v.IsSequence()) fail_at(v, field(key), "expected a list");
    return v;
  }

  void finish() const {
    for (const auto& kv : node_) {
      const std::string k = kv.first.Scalar();
      if (used_.count(k)) continue;
      const std::vector<std::string_view> known(asked_.begin(), asked_.end());
      const auto best = nearest_word(k, known);
      fail_at(kv.first, field(k), best ? fmt::format("unknown key, did you mean \"{}\"?", *best) : "unknown key");
    }
  }

  [[noreturn]] void fail(std::string_view key, std::string_view what) const {
    const YAML::Node v = node_[std::string(key)];
    fail_at(v ? v : node_, key.empty() ? path_ : field(key), what);
  }

  [[noreturn]] void fail_at(const YAML::Node& at, const std::string& path, std::string_view what) const {
    const YAML::Mark m = at.Mark();
    throw ScenarioError(fmt::format("{}:{}:{}: {}: {}", file_, m.line + 1, m.column + 1, path.empty() ? "(top)" : path, what));
  }

  std::int64_t integer_of(const YAML::Node& v, const std::string& path, std::int64_t min, std::int64_t max) const {
    std::int64_t i = 0;
    if (!v.IsScalar() || !YAML::convert<std::int64_t>::decode(v, i))
      fail_at(v, path, fmt::format("expected a whole number, got \"{}\"", v.IsScalar() ? v.Scalar() : "(not a value)"));
    if (i < min || i > max) fail_at(v, path, fmt::format("{} is out of range [{}, {}]", v.Scalar(), min, max));
    return i;
  }

  int line() const { return node_.Mark().line + 1; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

private:
  YAML::Node node_;
  const std::string& file_;
  std::string path_;
  std::set<std::string, std::less<>> used_;
  mutable std::set<std::string, std::less<>> asked_;  // every key looked for, for suggestions
};

constexpr std::int64_t kI32Min = std::numeric_limits<std::int32_t>::min();
constexpr std::int64_t kI32Max = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t kU32Max = std::numeric_limits<std::uint32_t>::max();

struct Context {
  std::string file;
  std::size_t slaves = 0;
  std::set<std::string> step_names;
  std::vector<std::string> slave_names;          // for signal points
  std::vector<network::NamedSignal> signals;      // the network file's
};

// A named signal of the network file, or a point ("di 0x6000:1", "x.home"). That the entry
// exists is checked when the run builds the network.
std::string signal_of(Map& m, std::string_view key, const Context& c) {
  const std::string s = m.string(key);
  try {
    (void)network::named_or_parsed_point(s, c.signals, c.slave_names);
  } catch (const std::invalid_argument& e) {
    m.fail(key, e.what());
  }
  return s;
}

int slave_of(Map& m, const Context& c, bool allow_all) {
  if (allow_all && !m.has("slave")) return 0;
  return static_cast<int>(m.integer("slave", allow_all ? 0 : 1, static_cast<std::int64_t>(c.slaves)));
}

std::int8_t mode_of(Map& m, std::string_view key) {
  const YAML::Node v = m.get(key);
  static const std::pair<std::string_view, std::int8_t> kNames[] = {
      {"pp", 1}, {"pv", 3}, {"tq", 4}, {"hm", 6}, {"ip", 7}, {"csp", 8}, {"csv", 9}, {"cst", 10}};
  if (v.IsScalar())
    for (const auto& [n, value] : kNames)
      if (v.Scalar() == n) return value;
  std::int64_t number = 0;
  if (v.IsScalar() && !YAML::convert<std::int64_t>::decode(v, number)) {
    std::vector<std::string_view> names;
    for (const auto& [n, value] : kNames) names.push_back(n);
    const auto best = nearest_word(v.Scalar(), names);
    m.fail_at(v, m.field(key), fmt::format("unknown mode \"{}\"{} (pp, pv, tq, hm, ip, csp, csv, cst, or a 6060h number)",
                                           v.Scalar(), best ? fmt::format(", did you mean \"{}\"?", *best) : ""));
  }
  return static_cast<std::int8_t>(m.integer_of(v, m.field(key), -128, 127));
}

AlTarget state_of(Map& m, std::string_view key) {
  const std::string s = m.string(key);
  if (s == "init") return AlTarget::init;
  if (s == "preop") return AlTarget::preop;
  if (s == "safeop") return AlTarget::safeop;
  if (s == "op") return AlTarget::op;
  if (s == "boot") return AlTarget::boot;
  m.fail(key, fmt::format("unknown AL state \"{}\" (init, preop, safeop, op, boot)", s));
}

// A time point: "250ms", or {on: EVENT, slave: N, step: NAME, delay: TIME}.
TimePoint time_point(Map& parent, std::string_view key, const Context& c) {
  const YAML::Node v = parent.get(key);
  TimePoint p;
  p.line = v.Mark().line + 1;
  if (v.IsScalar()) {
    const auto t = parse_time(v.Scalar());
    if (!t) parent.fail(key, fmt::format("expected a time with a unit (e.g. 250ms, 1.5s) or {{on: EVENT, delay: TIME}}, got \"{}\"", v.Scalar()));
    p.delay = *t;
    return p;
  }
  Map m(v, c.file, parent.field(key));
  const std::string on = m.string("on");
  static const std::pair<std::string_view, EventKind> kEvents[] = {
      {"start", EventKind::start}, {"preop", EventKind::preop}, {"safeop", EventKind::safeop}, {"op", EventKind::op},
      {"enabled", EventKind::enabled}, {"fault", EventKind::fault}, {"target_reached", EventKind::target_reached},
      {"step", EventKind::step}};
  bool found = false;
  for (const auto& [n, e] : kEvents)
    if (on == n) p.event = e, found = true;
  if (!found) m.fail("on", fmt::format("unknown event \"{}\" (start, preop, safeop, op, enabled, fault, target_reached, step)", on));
  if (p.event == EventKind::enabled || p.event == EventKind::fault || p.event == EventKind::target_reached)
    p.slave = slave_of(m, c, false);
  if (p.event == EventKind::step) {
    p.step = m.string("step");
    if (!c.step_names.count(p.step)) m.fail("step", fmt::format("no step is named \"{}\"", p.step));
  }
  p.delay = m.time_or("delay", 0);
  m.finish();
  return p;
}

// A fault step's fields as fault::read_fault asks for them; its errors carry the file position.
class MapFaultSource final : public fault::FaultFieldSource {
public:
  explicit MapFaultSource(Map& m) : m_(m) {}
  bool has(std::string_view field) const override { return m_.has(field); }
  std::string text(std::string_view field) override { return m_.string(field); }
  double real(std::string_view field) override { return m_.real(field); }
  std::int64_t integer(std::string_view field, std::int64_t min, std::int64_t max) override { return m_.integer(field, min, max); }
  Nanos time(std::string_view field) override { return m_.time(field); }
  std::optional<std::string> address_text(std::string_view field) override {
    const YAML::Node v = m_.get(field);  // a value that is no text is left to integer() to refuse
    if (!v.IsScalar() || !ecat::is_address_text(v.Scalar())) return std::nullopt;
    return v.Scalar();
  }
  [[noreturn]] void missing(std::string_view field, std::string_view why) override {
    m_.fail("", fmt::format("missing \"{}\": {}", field, why));
  }
  [[noreturn]] void invalid(std::string_view field, std::string_view what) override { m_.fail(field, what); }
  [[noreturn]] void out_of_range(std::string_view field, std::string_view rule) override { m_.fail(field, rule); }

private:
  Map& m_;
};

fault::FaultSpec fault_of(Map& m, const Context& c, std::string& id) {
  id = m.string_or("id", "");
  MapFaultSource source(m);
  const fault::FaultSpec f = fault::read_fault(source, static_cast<int>(c.slaves));
  m.finish();
  return f;
}

// equals (with mask), min, max, near with tolerance: at least one.
Condition condition_of(Map& m) {
  Condition k;
  if (m.has("equals")) k.equals = m.integer("equals", std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max());
  if (m.has("mask")) k.mask = m.integer("mask", 0, std::numeric_limits<std::int64_t>::max());
  if (m.has("min")) k.min = m.real("min");
  if (m.has("max")) k.max = m.real("max");
  if (m.has("near")) k.near = m.real("near");
  if (m.has("tolerance")) {
    k.tolerance = m.real("tolerance");
    if (!k.near) m.fail("tolerance", "goes with near");
    if (k.tolerance < 0) m.fail("tolerance", "must not be negative");
  }
  if (k.mask && !k.equals) m.fail("mask", "goes with equals");
  if (!k.equals && !k.min && !k.max && !k.near) m.fail("", "an expectation needs a condition: equals, min, max or near");
  return k;
}

SdoWriteAction sdo_write_of(Map& m, const Context& c) {
  SdoWriteAction a;
  a.slave = slave_of(m, c, false);
  a.index = static_cast<std::uint16_t>(m.integer("index", 0x1000, 0xFFFF));
  a.subindex = static_cast<std::uint8_t>(m.integer_or("subindex", 0, 255, 0));
  a.value = m.integer("value", std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max());
  m.finish();
  return a;
}

Action action_of(Map& step, const Context& c) {
  static const std::string_view kActions[] = {"state", "sdo_write", "sdo_read", "controlword", "mode", "enable", "disable",
                                              "target", "motion", "fault", "clear_fault", "acknowledge", "signal"};
  std::string_view which;
  for (const std::string_view a : kActions) {
    if (!step.has(a)) continue;
    if (!which.empty()) step.fail(a, fmt::format("a step has one action; this one has \"{}\" and \"{}\"", which, a));
    which = a;
  }
  if (which.empty()) {
    step.misspelt(kActions);
    step.fail("", "a step needs one action: state, sdo_write, sdo_read, controlword, mode, enable, disable, target, motion, fault, clear_fault, acknowledge or signal");
  }
  Map m = step.map(which);
  if (which == "state") {
    StateAction a{slave_of(m, c, true), state_of(m, "to")};
    m.finish();
    return a;
  }
  if (which == "sdo_write") return sdo_write_of(m, c);
  if (which == "signal") {
    SignalAction a{signal_of(m, "name", c)};
    const YAML::Node v = m.get("value");
    bool b = false;
    if (v.IsScalar() && (v.Scalar() == "true" || v.Scalar() == "false" || v.Scalar() == "on" || v.Scalar() == "off") &&
        YAML::convert<bool>::decode(v, b))
      a.value = b ? 1 : 0;
    else
      a.value = m.integer_of(v, m.field("value"), std::numeric_limits<std::int64_t>::min(),
                             std::numeric_limits<std::int64_t>::max());
    m.finish();
    return a;
  }
  if (which == "sdo_read") {
    SdoReadAction a;
    a.slave = slave_of(m, c, false);
    a.index = static_cast<std::uint16_t>(m.integer("index", 0x1000, 0xFFFF));
    a.subindex = static_cast<std::uint8_t>(m.integer_or("subindex", 0, 255, 0));
    if (m.has("equals") || m.has("min") || m.has("max") || m.has("near")) a.expect = condition_of(m);
    m.finish();
    return a;
  }
  if (which == "controlword") {
    ControlwordAction a{slave_of(m, c, false), static_cast<std::uint16_t>(m.integer("value", 0, 0xFFFF))};
    m.finish();
    return a;
  }
  if (which == "mode") {
    ModeAction a{slave_of(m, c, false), mode_of(m, "mode")};
    m.finish();
    return a;
  }
  if (which == "enable") {
    EnableAction a{slave_of(m, c, false), mode_of(m, "mode")};
    m.finish();
    return a;
  }
  if (which == "disable") {
    DisableAction a{slave_of(m, c, false)};
    m.finish();
    return a;
  }
  if (which == "target") {
    TargetAction a;
    a.slave = slave_of(m, c, false);
    if (m.has("position")) a.position = static_cast<std::int32_t>(m.integer("position", kI32Min, kI32Max));
    if (m.has("velocity")) a.velocity = static_cast<std::int32_t>(m.integer("velocity", kI32Min, kI32Max));
    if (m.has("torque")) a.torque = static_cast<std::int16_t>(m.integer("torque", -32768, 32767));
    if (m.has("relative")) a.relative = m.boolean("relative");
    if (!a.position && !a.velocity && !a.torque) m.fail("", "a target needs position, velocity or torque");
    m.finish();
    return a;
  }
  if (which == "motion") {
    MotionAction a;
    a.slave = slave_of(m, c, false);
    const std::string shape = m.string("shape");
    if (shape == "ramp") {
      a.shape = MotionAction::Shape::ramp;
      a.position = m.real("position");
      a.velocity = m.real("velocity");
      if (!(a.velocity > 0.0)) m.fail("velocity", "must be > 0 (user units per second)");
    } else if (shape == "sine") {
      a.shape = MotionAction::Shape::sine;
      a.amplitude = m.real("amplitude");
      a.frequency_hz = m.real("frequency");
      if (!(a.frequency_hz > 0.0)) m.fail("frequency", "must be > 0 (Hz)");
      a.duration = m.time("duration");
    } else {
      m.fail("shape", fmt::format("unknown motion shape \"{}\" (ramp, sine)", shape));
    }
    m.finish();
    return a;
  }
  if (which == "fault") {
    FaultAction a;
    a.fault = fault_of(m, c, a.id);
    return a;
  }
  if (which == "clear_fault") {
    ClearFaultAction a{m.string_or("id", "")};
    m.finish();
    return a;
  }
  AcknowledgeAction a{slave_of(m, c, false)};
  m.finish();
  return a;
}

Probe probe_of(Map& m, const Context& c) {
  Probe p;
  static const std::string_view kProbes[] = {"object", "al_state", "al_status_code", "register", "master", "signal"};
  std::string_view which;
  for (const std::string_view k : kProbes) {
    if (!m.has(k)) continue;
    if (!which.empty()) m.fail(k, fmt::format("an expectation measures one thing; this one has \"{}\" and \"{}\"", which, k));
    which = k;
  }
  if (which.empty()) {
    m.misspelt(kProbes);
    m.fail("", "an expectation needs what it measures: object, al_state, al_status_code, register, master or signal");
  }
  if (which == "signal") {
    p.kind = Probe::Kind::signal;
    p.signal = signal_of(m, "signal", c);
    return p;
  }
  if (which == "master") {
    const std::string counter = m.string("master");
    if (counter == "wrong_wkc") p.kind = Probe::Kind::master_wrong_wkc;
    else if (counter == "lost_frames") p.kind = Probe::Kind::master_lost_frames;
    else m.fail("master", fmt::format("unknown master counter \"{}\" (wrong_wkc, lost_frames)", counter));
    return p;
  }
  p.slave = slave_of(m, c, false);
  if (which == "object") {
    p.kind = Probe::Kind::object;
    p.index = static_cast<std::uint16_t>(m.integer("object", 0x1000, 0xFFFF));
    p.subindex = static_cast<std::uint8_t>(m.integer_or("subindex", 0, 255, 0));
  } else if (which == "register") {
    p.kind = Probe::Kind::esc_register;
    p.index = static_cast<std::uint16_t>(m.integer("register", 0, 0x0FFF));
    p.size = static_cast<std::uint8_t>(m.integer_or("size", 1, 4, 2));
    if (p.size == 3) m.fail("size", "a register is read as 1, 2 or 4 bytes");
  } else if (which == "al_state") {
    p.kind = Probe::Kind::al_state;
    m.get("al_state");  // the value is the expected state, read as the condition below
  } else {
    p.kind = Probe::Kind::al_status_code;
    m.get("al_status_code");
  }
  return p;
}

Expectation expectation_of(Map& m, const Context& c, std::size_t i) {
  Expectation e;
  e.line = m.line();
  e.probe = probe_of(m, c);
  Condition& k = e.condition;
  if (e.probe.kind == Probe::Kind::al_state) {
    k.equals = static_cast<std::int64_t>(state_of(m, "al_state"));
    k.mask = 0x0F;
  } else if (e.probe.kind == Probe::Kind::al_status_code) {
    k.equals = m.integer("al_status_code", 0, 0xFFFF);
  } else {
    k = condition_of(m);
  }
  const int timings = int(m.has("at")) + int(m.has("by")) + int(m.has("always"));
  if (timings != 1) m.fail("", "an expectation needs exactly one of at, by or always");
  if (m.has("at")) {
    e.timing = Expectation::Timing::at;
    e.when = time_point(m, "at", c);
  } else if (m.has("by")) {
    e.timing = Expectation::Timing::by;
    e.when = time_point(m, "by", c);
  } else {
    e.timing = Expectation::Timing::always;
    if (!m.boolean("always")) m.fail("always", "write always: true, or use at/by");
    if (m.has("until")) e.until = time_point(m, "until", c);
  }
  if (m.has("from")) {
    if (e.timing == Expectation::Timing::at) m.fail("from", "goes with by or always");
    e.from = time_point(m, "from", c);
  }
  e.name = m.string_or("name", "");
  if (e.name.empty()) e.name = fmt::format("expect[{}] (line {})", i, e.line);
  m.finish();
  return e;
}

const profile::ProductProfile* lookup(std::deque<profile::ProductProfile>& keep, std::string_view id) {
  try {
    keep.push_back(esi::is_esi_reference(id) ? esi::load_esi_device(id)->profile : profile::load_profile(id));
    return &keep.back();
  } catch (const profile::ProfileError&) {
    return nullptr;
  }
}

}  // namespace

Scenario parse_scenario(std::string_view text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw ScenarioError(fmt::format("{}:{}:{}: {}", file, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  if (!root.IsMap()) throw ScenarioError(fmt::format("{}:1:1: a scenario file is a mapping (name, segment, master, timeline, expect)", file));
  Scenario s;
  s.file = file;
  Context c;
  c.file = file;
  Map top(root, c.file, "");
  s.name = top.string_or("name", fs::path(file).stem().string());
  s.description = top.string_or("description", "");
  s.seed = static_cast<std::uint64_t>(top.integer_or("seed", 0, std::numeric_limits<std::int64_t>::max(), 1));
  s.duration = top.time("duration");
  if (s.duration <= 0) top.fail("duration", "must be > 0");
  s.trace_period = top.time_or("trace_period", 0);
  if (top.has("expect_stop")) {
    s.expect_stop = top.string("expect_stop");
    s.expect_stop_line = root["expect_stop"].Mark().line + 1;
    if (s.expect_stop.empty()) top.fail("expect_stop", "give the text the stop message must contain");
  }

  Map segment = top.map("segment");
  s.hop_delay = segment.time_or("hop_delay", 500);
  std::deque<profile::ProductProfile> products;
  const fs::path base = fs::path(file).parent_path();
  // `path` as given (found beside the scenario when relative), or already resolved.
  auto plant_of = [&](Map& m, const std::string& rel, bool resolved = false) -> plant::PlantDescription {
    const fs::path path = resolved || fs::path(rel).is_absolute() ? fs::path(rel) : base / rel;
    std::optional<plant::PlantDescription> plant;
    try {
      plant = plant::load_plant_file(path.string(), [&](std::string_view id) -> std::optional<plant::MotorCatalogue> {
        const profile::ProductProfile* product = lookup(products, id);
        if (!product) return std::nullopt;
        return drive::motor_catalogue(*product);
      });
    } catch (const std::exception& e) {
      m.fail("plant", e.what());
    }
    if (plant->axes.empty()) m.fail("plant", "the plant has no axis for the drive");
    return *plant;
  };
  if (segment.has("network") && segment.has("slaves"))
    segment.fail("network", "a segment is a network file or a list of slaves, not both");
  if (segment.has("network")) {
    const std::string rel = segment.string("network");
    s.network_file = fs::path(rel).is_absolute() ? rel : (base / rel).string();
    machine::NetworkFile nf;
    try {
      nf = machine::load_network_file(s.network_file);
    } catch (const machine::NetworkFileError& e) {
      segment.fail("network", e.what());
    }
    s.network = machine::network_options(nf);
    for (const machine::NetworkSlave& ns : nf.slaves) {
      SlaveSpec sl;
      sl.line = segment.line();
      sl.product = ns.device;
      if (!ns.plant_file.empty()) sl.plant = plant_of(segment, ns.plant_file, true);
      s.slaves.push_back(std::move(sl));
    }
    c.slave_names = s.network.slave_names;
    c.signals = s.network.signals;
    // The file's armed faults are steps at their times, before the timeline's.
    for (const machine::ArmedFault& a : nf.faults) {
      Step st;
      st.line = segment.line();
      st.when.delay = a.at;
      st.when.line = st.line;
      st.action = FaultAction{a.spec, ""};
      s.steps.push_back(std::move(st));
    }
  }
  const YAML::Node slaves = segment.has("network") ? YAML::Node(YAML::NodeType::Sequence) : segment.sequence("slaves");
  if (!segment.has("network") && slaves.size() == 0) segment.fail("slaves", "a segment needs at least one slave");
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    Map m(slaves[i], c.file, fmt::format("segment.slaves[{}]", i));
    SlaveSpec sl;
    sl.line = m.line();
    sl.product = m.string("product");
    // An ESI device's file is found beside the scenario, as its plant files are.
    if (esi::is_esi_reference(sl.product) && !fs::path(sl.product).is_absolute()) sl.product = (base / sl.product).string();
    if (esi::is_esi_reference(sl.product)) {
      try {
        (void)esi::load_esi_device(sl.product);
      } catch (const profile::ProfileError& e) {
        m.fail("product", e.what());
      }
    }
    if (!lookup(products, sl.product)) {
      std::string known;
      for (const std::string& id : profile::known_products()) known += (known.empty() ? "" : ", ") + id;
      m.fail("product", fmt::format("unknown product \"{}\" ({})", sl.product, known));
    }
    if (m.has("plant")) sl.plant = plant_of(m, m.string("plant"));
    m.finish();
    s.slaves.push_back(std::move(sl));
    c.slave_names.push_back(fmt::format("{}", i + 1));
  }
  segment.finish();
  c.slaves = s.slaves.size();

  if (top.has("master")) {
    Map m = top.map("master");
    s.master.cycle = m.time_or("cycle", 1'000'000);
    if (s.master.cycle < 125'000) m.fail("cycle", "the built-in master cycles at 125us or slower");
    if (m.has("dc")) s.master.dc = m.boolean("dc");
    if (m.has("start_state")) s.master.start_state = state_of(m, "start_state");
    if (m.has("startup")) {
      const YAML::Node list = m.sequence("startup");
      for (std::size_t i = 0; i < list.size(); ++i) {
        Map w(list[i], c.file, fmt::format("master.startup[{}]", i));
        s.master.startup.push_back(sdo_write_of(w, c));
      }
    }
    m.finish();
  }

  if (top.has("timeline")) {
    const YAML::Node list = top.sequence("timeline");
    // Names first, so a step can wait for one defined further down.
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (list[i].IsMap() && list[i]["name"] && list[i]["name"].IsScalar()) {
        if (!c.step_names.insert(list[i]["name"].Scalar()).second)
          Map(list[i], c.file, fmt::format("timeline[{}]", i)).fail("name", "two steps have this name");
      }
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
      Map m(list[i], c.file, fmt::format("timeline[{}]", i));
      Step st;
      st.line = m.line();
      st.name = m.string_or("name", "");
      st.when = time_point(m, "at", c);
      st.action = action_of(m, c);
      m.finish();
      s.steps.push_back(std::move(st));
    }
  }
  if (top.has("expect")) {
    const YAML::Node list = top.sequence("expect");
    for (std::size_t i = 0; i < list.size(); ++i) {
      Map m(list[i], c.file, fmt::format("expect[{}]", i));
      s.expectations.push_back(expectation_of(m, c, i));
    }
  }
  top.finish();
  return s;
}

Scenario load_scenario_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ScenarioError(fmt::format("{}: cannot read the file", path));
  std::stringstream text;
  text << in.rdbuf();
  return parse_scenario(text.str(), path);
}

std::vector<std::string> scenario_files(const std::string& file_or_directory) {
  std::error_code ec;
  if (!fs::exists(file_or_directory, ec)) throw ScenarioError(fmt::format("{}: no such file or directory", file_or_directory));
  if (!fs::is_directory(file_or_directory, ec)) return {file_or_directory};
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(file_or_directory, ec)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".yaml" || ext == ".yml")) files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw ScenarioError(fmt::format("{}: no scenario files (*.yaml) in this directory", file_or_directory));
  return files;
}

}  // namespace vdrive::scenario
