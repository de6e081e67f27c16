#include "vdrive/web/line_record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <variant>

#include "master/al_state.hpp"
#include "master/coe.hpp"
#include "vdrive/profile/product_profile.hpp"
#include "vdrive/web/cia402_text.hpp"

namespace vdrive::web {
namespace {

using json = nlohmann::json;

// DC counts as locked while the system time difference stays within 1 us (ETG.1020's usual
// synchronisation target; the page shows the difference itself too).
constexpr std::int64_t kDcLockNs = 1000;

std::string al_state_text(std::uint16_t al_status) {
  return std::string(master::to_string(static_cast<master::AlState>(al_status & 0x0F)));
}

double seconds(Nanos t) { return static_cast<double>(t) / 1e9; }

// CSV field: quoted when it holds a comma, quote or line break.
std::string csv(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

LineRecord::LineRecord(std::vector<SlaveInfo> slaves, LineIdentity identity, Nanos origin, std::size_t later_slaves)
    : slaves_(std::move(slaves)), identity_(std::move(identity)), origin_(origin), axes_(slaves_.size()),
      registers_(slaves_.size()), later_(later_slaves) {}

std::string LineRecord::alarm_text(std::size_t i, std::uint16_t error_code) const {
  // Several alarms can show one 603Fh value (A6B 27.1, 27.4, 27.6, 27.7 all FF1Bh): then all are named.
  std::string codes;
  const profile::AlarmSpec* only = nullptr;
  int count = 0;
  if (slaves_[i].profile != nullptr) {
    for (const profile::AlarmSpec& a : slaves_[i].profile->alarms) {
      if (a.error_code != error_code) continue;
      codes += (codes.empty() ? "" : ", ") + a.code;
      only = &a;
      ++count;
    }
  }
  if (count == 1) return fmt::format("{} {}", only->code, only->name_en.empty() ? only->name : only->name_en);
  if (count > 1) return fmt::format("one of {}", codes);
  return fmt::format("603Fh {:04X}h", error_code);
}

void LineRecord::push_event(Event e) {
  e.seq = ++event_seq_;
  events_.push_back(std::move(e));
  while (events_.size() > kEvents) events_.pop_front();
}

void LineRecord::add(const telemetry::Sample& sample) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (const auto* a = std::get_if<telemetry::AxisSample>(&sample)) {
    if (a->slave < 1 || a->slave > axes_.size()) return;
    Axis& axis = axes_[a->slave - 1];
    axis.latest = *a;
    axis.points.push_back({++sample_seq_, a->time, a->target_position, a->position, a->velocity, a->following_error, a->torque});
    while (axis.points.size() > kPointsPerAxis) axis.points.pop_front();
  } else if (const auto* b = std::get_if<telemetry::BusSample>(&sample)) {
    bus_ = *b;
  } else if (const auto* e = std::get_if<telemetry::EventSample>(&sample)) {
    Event ev{0, e->time, e->slave, telemetry::event_kind_name(e->kind), e->value, e->previous, std::string(e->text.data())};
    const std::size_t i = static_cast<std::size_t>(e->slave) - 1;
    if (e->slave >= 1 && i < slaves_.size()) {
      if (e->kind == telemetry::EventKind::al_state) {
        ev.text = fmt::format("{} -> {}", al_state_text(static_cast<std::uint16_t>(e->previous)),
                              al_state_text(static_cast<std::uint16_t>(e->value)));
        if ((e->value & 0x10) != 0) ev.text += " (AL error)";
      } else if (e->kind == telemetry::EventKind::alarm_raised) {
        ev.text = fmt::format("alarm {} (603Fh {:04X}h)", alarm_text(i, static_cast<std::uint16_t>(e->value)), e->value);
        axes_[i].emergencies.push_back({e->time, static_cast<std::uint16_t>(e->value), alarm_text(i, static_cast<std::uint16_t>(e->value))});
        while (axes_[i].emergencies.size() > kEmergencies) axes_[i].emergencies.pop_front();
      } else if (e->kind == telemetry::EventKind::alarm_cleared) {
        ev.text = fmt::format("alarm {} cleared", alarm_text(i, static_cast<std::uint16_t>(e->previous)));
      }
    }
    push_event(std::move(ev));
  }
}

void LineRecord::set_registers(const std::vector<SlaveRegisters>& registers, Nanos now) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t i = 0; i < std::min(registers.size(), registers_.size()); ++i) {
    const SlaveRegisters& r = registers[i];
    // An SDO abort a master got since the last copy (only the last one of several is known).
    if (registers_seen_ && r.sdo_aborts > registers_[i].sdo_aborts) {
      const std::uint32_t more = r.sdo_aborts - registers_[i].sdo_aborts;
      push_event({0, now, static_cast<int>(i + 1), "sdo_abort", r.abort_code, 0,
                  fmt::format("{:04X}h:{:02X} abort 0x{:08X} {}{}", r.abort_index, r.abort_subindex, r.abort_code,
                              master::sdo_abort_text(r.abort_code),
                              more > 1 ? fmt::format(" (the last of {})", more) : std::string())});
    }
    registers_[i] = r;
  }
  registers_seen_ = true;
}

std::vector<std::uint16_t> LineRecord::stations() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::uint16_t> s;
  for (const SlaveRegisters& r : registers_) s.push_back(r.station_address);
  for (const LaterSlave& l : later_) s.push_back(l.view.is_object() ? l.view.value("address", std::uint16_t{0}) : std::uint16_t{0});
  return s;
}

void LineRecord::set_faults(std::vector<control::FaultStatus> faults) {
  const std::lock_guard<std::mutex> lock(mutex_);
  faults_ = std::move(faults);
}

void LineRecord::note(int slave, const std::string& kind, std::int64_t value, std::int64_t previous, const std::string& text, Nanos time) {
  const std::lock_guard<std::mutex> lock(mutex_);
  push_event({0, time, slave, kind, value, previous, text});
}

void LineRecord::set_scenario(const ScenarioView& scenario) {
  const std::lock_guard<std::mutex> lock(mutex_);
  scenario_ = scenario;
}

json LineRecord::drive_json(std::size_t i) const {
  const Axis& axis = axes_[i];
  if (!slaves_[i].drive) return nullptr;
  json d = json::object();
  const telemetry::AxisSample a = axis.latest.value_or(telemetry::AxisSample{});
  d["statusword"] = a.statusword;
  d["state"] = axis.latest ? pds_state_name(a.statusword) : "unknown";
  d["controlword"] = a.controlword;
  d["mode"] = a.mode;
  d["mode_name"] = mode_name(a.mode);
  d["position"] = a.position;
  d["target_position"] = a.target_position;
  d["velocity"] = a.velocity;
  d["torque"] = a.torque;
  d["following_error"] = a.following_error;
  d["error_code"] = a.error_code;
  d["digital_inputs"] = a.digital_inputs;
  d["probe_status"] = a.probe_status;
  d["probe_position1"] = a.probe_position1;
  d["alarm"] = nullptr;
  if (a.error_code != 0) {
    json alarm = {{"code", nullptr}, {"name", fmt::format("603Fh {:04X}h", a.error_code)}, {"error_code", a.error_code}, {"warning", false}};
    // The drive's own newest alarm when it shows this 603Fh; else the first of the table that does.
    const profile::AlarmSpec* newest = registers_[i].alarm;
    const profile::AlarmSpec* spec = newest != nullptr && newest->error_code == a.error_code
                                         ? newest : slaves_[i].profile->alarm_with_error_code(a.error_code);
    if (spec != nullptr) {
      alarm["code"] = spec->code;
      alarm["name"] = spec->name_en.empty() ? spec->name : spec->name_en;
      alarm["warning"] = spec->warning;
    }
    d["alarm"] = std::move(alarm);
  }
  json emergencies = json::array();
  for (const Emergency& e : axis.emergencies)
    emergencies.push_back({{"time_ns", e.time - origin_}, {"error_code", e.error_code}, {"text", e.text}});
  d["emergencies"] = std::move(emergencies);
  return d;
}

json LineRecord::slave_json(std::size_t i) const {
  const SlaveInfo& s = slaves_[i];
  const SlaveRegisters& r = registers_[i];
  const bool error = (r.al_status & 0x10) != 0;
  json j = {{"position", s.position}, {"name", s.name}, {"product", s.product}, {"product_name", s.product_name},
            {"vendor_id", s.vendor_id}, {"product_code", s.product_code}, {"revision", s.revision},
            {"address", r.station_address}, {"alias", r.alias}, {"al_state", r.al_status & 0x0F},
            {"al_state_name", al_state_text(r.al_status)}, {"al_error", error},
            {"al_status_code", r.al_status_code},
            {"al_status_text", error || r.al_status_code != 0 ? std::string(master::al_status_code_text(r.al_status_code)) : "No error"},
            {"rx_errors", r.rx_errors}, {"lost_links", r.lost_links}, {"parent", s.parent}, {"parent_port", s.parent_port},
            {"answers", true}};
  j["dc"] = {{"enabled", r.dc_active}, {"system_time_difference_ns", r.system_time_difference},
             {"locked", r.dc_active && std::llabs(r.system_time_difference) < kDcLockNs}};
  j["drive"] = drive_json(i);
  return j;
}

json LineRecord::line(Nanos now) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  json j = {{"api", "v1"}, {"version", identity_.version}, {"source", identity_.source},
            {"interface", identity_.interface}, {"time_ns", now - origin_}, {"token_required", identity_.token_required}};
  std::uint64_t rx = 0, lost = 0;
  for (const SlaveRegisters& r : registers_) {
    for (const std::uint8_t c : r.rx_errors) rx += c;
    for (const std::uint8_t c : r.lost_links) lost += c;
  }
  // The line's frames are counted where the master is; stalls and the ports' counters in every part.
  std::uint64_t stalls = bus_.host_stalls;
  std::int64_t longest = bus_.longest_host_stall;
  for (const LaterSlave& l : later_) {
    if (!l.view.is_object()) continue;
    for (const json& c : l.view.value("rx_errors", json::array())) rx += c.get<std::uint64_t>();
    for (const json& c : l.view.value("lost_links", json::array())) lost += c.get<std::uint64_t>();
  }
  for (const auto& [first, p] : part_stalls_) {
    stalls += p.count;
    longest = std::max(longest, p.longest_ns);
  }
  j["counters"] = {{"frames_in", bus_.frames_in}, {"frames_out", bus_.frames_out}, {"frames_dropped", bus_.frames_dropped},
                   {"send_failed", bus_.send_failed}, {"rx_errors", rx}, {"lost_links", lost},
                   {"host_stalls", stalls}, {"longest_host_stall_ns", longest}};
  json slaves = json::array();
  for (std::size_t i = 0; i < slaves_.size(); ++i) slaves.push_back(slave_json(i));
  for (std::size_t k = 0; k < later_.size(); ++k) slaves.push_back(later_slave_json(k));
  j["slaves"] = std::move(slaves);
  json faults = json::array();
  for (const control::FaultStatus& f : faults_)
    faults.push_back({{"id", f.id}, {"kind", f.kind}, {"description", f.description}, {"elapsed_ns", f.elapsed}, {"remaining_ns", f.remaining}});
  j["faults"] = std::move(faults);
  j["scenario"] = nullptr;
  if (scenario_) {
    json expectations = json::array();
    for (const ExpectationView& e : scenario_->expectations)
      expectations.push_back({{"line", e.line}, {"text", e.name}, {"state", e.state}, {"detail", e.detail}});
    // Elapsed on the line's clock from the start (the runner reports whole seconds only); the verdict
    // once every expectation is decided (the page ends with the run, so it would never see it).
    const Nanos elapsed = scenario_->started > 0 ? std::max(scenario_->elapsed, now - scenario_->started) : scenario_->elapsed;
    std::string state = scenario_->state;
    const bool open = std::any_of(scenario_->expectations.begin(), scenario_->expectations.end(),
                                  [](const ExpectationView& e) { return e.state == "open"; });
    if (state == "running" && !open && !scenario_->expectations.empty())
      state = std::all_of(scenario_->expectations.begin(), scenario_->expectations.end(),
                          [](const ExpectationView& e) { return e.state == "met"; }) ? "passed" : "failed";
    j["scenario"] = {{"name", scenario_->name}, {"state", state}, {"elapsed_ns", scenario_->duration > 0 ? std::min(elapsed, scenario_->duration) : elapsed},
                     {"duration_ns", scenario_->duration}, {"log", scenario_->log}, {"expectations", std::move(expectations)}};
  }
  return j;
}

json LineRecord::samples(std::uint64_t since, int slave) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  json axes = json::array();
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    if (!slaves_[i].drive || (slave != 0 && slave != static_cast<int>(i + 1))) continue;
    axes.push_back(points_json(static_cast<int>(i + 1), axes_[i].points, since));
  }
  for (std::size_t k = 0; k < later_.size(); ++k) {
    const int position = static_cast<int>(slaves_.size() + k + 1);
    const json& view = later_[k].view;
    if (!view.is_object() || view.value("drive", json()).is_null() || (slave != 0 && slave != position)) continue;
    axes.push_back(points_json(position, later_[k].points, since));
  }
  return {{"seq", sample_seq_}, {"axes", std::move(axes)}};
}

json LineRecord::points_json(int slave, const std::deque<Point>& points, std::uint64_t since) const {
  json t = json::array(), target = json::array(), pos = json::array(), vel = json::array(), torque = json::array(), ferr = json::array();
  // Points are in sequence order: skip to the first new one.
  auto it = std::upper_bound(points.begin(), points.end(), since, [](std::uint64_t s, const Point& p) { return s < p.seq; });
  for (; it != points.end(); ++it) {
    t.push_back(seconds(it->time - origin_));
    target.push_back(it->target_position);
    pos.push_back(it->position);
    vel.push_back(it->velocity);
    torque.push_back(it->torque);
    ferr.push_back(it->following_error);
  }
  return {{"slave", slave}, {"t", std::move(t)}, {"target_position", std::move(target)}, {"position", std::move(pos)},
          {"velocity", std::move(vel)}, {"torque", std::move(torque)}, {"following_error", std::move(ferr)}};
}

json LineRecord::events(std::uint64_t since, const std::string& kind, int slave) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  json list = json::array();
  for (const Event& e : events_) {
    if (e.seq <= since || (!kind.empty() && e.kind != kind) || (slave != 0 && e.slave != slave)) continue;
    list.push_back({{"seq", e.seq}, {"time_ns", e.time - origin_}, {"slave", e.slave}, {"kind", e.kind},
                    {"value", e.value}, {"previous", e.previous}, {"text", e.text}});
  }
  return {{"seq", event_seq_}, {"events", std::move(list)}};
}

std::string LineRecord::events_csv(const std::string& kind, int slave) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::string out = "seq,time_ns,slave,kind,value,previous,text\n";
  for (const Event& e : events_) {
    if ((!kind.empty() && e.kind != kind) || (slave != 0 && e.slave != slave)) continue;
    out += fmt::format("{},{},{},{},{},{},{}\n", e.seq, e.time - origin_, e.slave, csv(e.kind), e.value, e.previous, csv(e.text));
  }
  return out;
}

std::uint64_t LineRecord::sample_seq() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return sample_seq_;
}

std::uint64_t LineRecord::event_seq() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return event_seq_;
}

}  // namespace vdrive::web
