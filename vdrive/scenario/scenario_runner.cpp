#include "vdrive/scenario/scenario_runner.hpp"

#include <chrono>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "ethercat/registers.hpp"
#include "master/cyclic_task.hpp"
#include "master/dc.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "master/process_data.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/raw_socket_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/od/entry_value.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/runtime/host_stalls.hpp"
#include "vdrive/scenario/axis_control.hpp"
#include "vdrive/scenario/event_log.hpp"
#include "vdrive/scenario/pcapng_writer.hpp"
#include "vdrive/scenario/realtime_wire.hpp"
#include "vdrive/scenario/trace_writer.hpp"
#include "vdrive/scenario/virtual_wire.hpp"

namespace vdrive::scenario {
namespace {

constexpr std::uint16_t kAlStatus = ecat::reg::kAlStatus, kAlStatusCode = ecat::reg::kAlStatusCode;
constexpr std::uint64_t kSafeOpCycles = 100;  // cyclic frames in Safe-Op before Op is requested
constexpr Nanos kMailboxTimeout = 20'000'000;

// A step or the start-up that cannot go on; its message becomes ScenarioResult::error.
class RunError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

std::vector<std::string> product_ids(const Scenario& s) {
  std::vector<std::string> ids;
  for (const SlaveSpec& sl : s.slaves) ids.push_back(sl.product);
  return ids;
}

network::NetworkOptions network_options(const Scenario& s) {
  network::NetworkOptions o = s.network;
  o.hop_delay = s.hop_delay;
  o.plants.clear();
  for (const SlaveSpec& sl : s.slaves) o.plants.push_back(sl.plant);
  return o;
}

std::string_view state_name(std::uint16_t al) {
  switch (al & 0x0F) {
    case 1: return "Init";
    case 2: return "Pre-Op";
    case 3: return "Boot";
    case 4: return "Safe-Op";
    case 8: return "Op";
    default: return "?";
  }
}

class Run {
public:
  Run(const Scenario& s, const RunOptions& o)
      : s_(s), o_(o), ids_(product_ids(s)), clock_(make_clock(o)), network_(ids_, *clock_, network_options(s)),
        impairment_(o.seed.value_or(s.seed)), wire_(make_wire()), faults_(network_, &impairment_),
        events_(s.slaves.size()), axes_(s.slaves.size()), ran_(s.steps.size(), false) {
    result_.name = s.name;
    result_.file = s.file;
    if (o.line_interface.empty() || !o.master_interface.empty()) master_ = std::make_unique<master::Master>(*wire_, *clock_);
    if (!o.pcap_path.empty()) {
      capture_ = std::make_unique<PcapngWriter>(o.pcap_path);
      wire_->set_capture(capture_.get());
    }
    if (!o.trace_path.empty()) trace_ = std::make_unique<TraceWriter>(o.trace_path);
    if (auto* rt = dynamic_cast<RealtimeWire*>(wire_.get())) loop_counters_ = &rt->counters();
    if (auto* rt = dynamic_cast<RealtimeWire*>(wire_.get()); rt && o.line_tap) {
      tap_ = o.line_tap(network_, rt->line(), *clock_, rt->counters());
      if (tap_) rt->attach(tap_->link(), &tap_->service());
    }
    for (const Expectation& e : s.expectations) checks_.emplace_back(e);
  }

  ScenarioResult go() {
    const auto wall = std::chrono::steady_clock::now();
    try {
      check_probes();
      start_faults();
      start();
      loop();
    } catch (const RunError& e) {
      fail(e.what());
    } catch (const fault::FaultError& e) {
      fail(e.what());
    } catch (const master::SdoAbort& e) {
      fail(fmt::format("{}", e.what()));
    } catch (const std::exception& e) {
      fail(fmt::format("the master: {}", e.what()));
    }
    result_.ended = clock_->now();
    for (ExpectationCheck& c : checks_) {
      const bool open = !c.result().decided;
      c.finish(clock_->now(), events_);
      if (open && o_.decided) o_.decided(c.result());
    }
    for (const ExpectationCheck& c : checks_) result_.expectations.push_back(c.result());
    for (ExpectationResult& r : step_results_) result_.expectations.push_back(std::move(r));
    if (!s_.expect_stop.empty()) {
      ExpectationResult stop;
      stop.name = "the run stops: " + s_.expect_stop;
      stop.line = s_.expect_stop_line;
      stop.decided = true;
      stop.time = clock_->now();
      stop.passed = result_.error.find(s_.expect_stop) != std::string::npos;
      stop.message = result_.error.empty() ? "the run did not stop" : "stopped: " + result_.error;
      if (stop.passed) result_.error.clear();
      result_.expectations.push_back(std::move(stop));
    }
    result_.simulated = clock_->now();
    if (task_) {
      result_.cycles = task_->stats().cycles;
      result_.wrong_wkc = task_->stats().wrong_wkc;
      result_.lost_frames = task_->stats().lost_frames;
    }
    if (loop_counters_ != nullptr) {
      note_stalls();
      result_.host_stalls = loop_counters_->stalls.count();
      result_.longest_host_stall = loop_counters_->stalls.longest();
    }
    result_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
    return std::move(result_);
  }

private:
  static std::unique_ptr<Clock> make_clock(const RunOptions& o) {
    if (o.line_interface.empty()) return std::make_unique<VirtualClock>();
    return std::make_unique<MonotonicClock>();
  }
  std::unique_ptr<ScenarioWire> make_wire() {
    if (auto* v = dynamic_cast<VirtualClock*>(clock_.get())) return std::make_unique<VirtualWire>(network_, *v, impairment_);
    line_link_ = std::make_unique<link::RawSocketLink>(o_.line_interface);
    if (!o_.master_interface.empty()) master_link_ = std::make_unique<link::RawSocketLink>(o_.master_interface);
    return std::make_unique<RealtimeWire>(network_, *clock_, impairment_, master_link_.get(), *line_link_);
  }
  master::Master& master(std::string_view what) {
    if (!master_) throw RunError(fmt::format("{}: an external master drives this line; the step needs the built-in master", what));
    return *master_;
  }

  void say(const std::string& line) {
    const std::string text = fmt::format("{:>10.3f} ms  {}", static_cast<double>(clock_->now()) / 1e6, line);
    result_.log.push_back(text);
    if (o_.log) o_.log(text);
  }
  void fail(const std::string& what) {
    say("stopped: " + what);
    result_.error = what;
  }

  bool is_drive(std::size_t i) const { return network_.profile(i).modes.supported_drive_modes != 0 && !network_.profile(i).modes.modes.empty(); }

  // A signal a step sets or an expectation reads, resolved once; what does not exist is the
  // scenario's mistake, with its line.
  const network::SignalAccess& signal(const std::string& name, int line) {
    if (const auto it = signals_.find(name); it != signals_.end()) return it->second;
    try {
      return signals_.emplace(name, network_.resolve(network_.point_of(name))).first->second;
    } catch (const std::invalid_argument& e) {
      throw RunError(fmt::format("{}:{}: signal \"{}\": {}", s_.file, line, name, e.what()));
    }
  }

  // Objects and signals the steps and expectations use must exist in the products, or the
  // scenario is wrong.
  void check_probes() {
    for (const Step& st : s_.steps) {
      if (const auto* a = std::get_if<SignalAction>(&st.action)) {
        try {
          signal(a->signal, st.line).check(a->value);
        } catch (const std::out_of_range& e) {
          throw RunError(fmt::format("{}:{}: signal \"{}\": {}", s_.file, st.line, a->signal, e.what()));
        }
      }
    }
    for (const Expectation& e : s_.expectations) {
      if (e.probe.kind == Probe::Kind::signal) (void)signal(e.probe.signal, e.line);
      if (e.probe.kind != Probe::Kind::object) continue;
      const auto i = static_cast<std::size_t>(e.probe.slave - 1);
      if (!network_.firmware(i).objects().dictionary().find(e.probe.index, e.probe.subindex))
        throw RunError(fmt::format("{}:{}: {}: slave {} ({}) has no object {:04X}h:{:02X}", s_.file, e.line, e.name,
                                   e.probe.slave, network_.profile(i).id, e.probe.index, e.probe.subindex));
    }
  }

  // Faults at time 0 act before the master's first frame.
  void start_faults() {
    for (std::size_t k = 0; k < s_.steps.size(); ++k) {
      const Step& st = s_.steps[k];
      if (st.when.event == EventKind::start && st.when.delay == 0 && std::holds_alternative<FaultAction>(st.action)) {
        perform(st);
        ran_[k] = true;
        events_.step_ran(st.name, clock_->now());
      }
    }
  }

  std::string al_summary() {
    std::string text;
    for (std::size_t i = 0; i < network_.size(); ++i)
      text += fmt::format(" slave {} {} 0x{:04X};", i + 1, state_name(peek16(i, kAlStatus)), peek16(i, kAlStatusCode));
    return text;
  }

  std::uint16_t peek16(std::size_t i, std::uint16_t address) { return network_.esc(i).peek_u16(address); }

  void start() {
    // Mailbox steps hold the cyclic frames while they wait (see the header): a short timeout keeps
    // a lost reply and its repeat request well inside the drives' 100 ms SM watchdog.
    if (!master_) return;  // an external master takes the line up
    master_->set_mailbox_timeout(kMailboxTimeout);
    const std::size_t found = master_->scan();
    say(fmt::format("scan: {} slaves", found));
    if (found != network_.size()) throw RunError(fmt::format("the scan found {} slaves, the segment has {}", found, network_.size()));
    if (s_.master.start_state == AlTarget::init) return;
    go_up_to(s_.master.start_state);
  }

  // Pre-Op with the start-up SDOs, then the process data and DC, Safe-Op, and Op in the cycles.
  void go_up_to(AlTarget target) {
    master::Master& m = master("state");
    if (!m.request_state(master::AlState::PreOp)) throw RunError("not every slave reached Pre-Op:" + al_summary());
    say("Pre-Op");
    for (const SdoWriteAction& w : s_.master.startup) sdo_write(w);
    if (target == AlTarget::preop) return;
    for (std::size_t i = 0; i < network_.size(); ++i) {
      if (!is_drive(i)) continue;
      try {
        AxisControl::map_pdos(m, i);
      } catch (const std::exception& e) {
        throw RunError(fmt::format("slave {}: the CiA 402 PDO mapping was refused: {}", i + 1, e.what()));
      }
    }
    std::vector<std::string> notes;
    layout_ = master::configure_process_data(m, &notes);
    std::uint32_t start = UINT32_MAX;
    for (const master::Slave& sl : m.slaves()) {
      if (sl.process_data.output_bytes) start = std::min(start, sl.process_data.output_logical);
      if (sl.process_data.input_bytes) start = std::min(start, sl.process_data.input_logical);
    }
    for (std::size_t i = 0; i < network_.size(); ++i) {
      const master::SlaveProcessData& pd = m.slaves()[i].process_data;
      if (is_drive(i) && !axes_[i].locate(pd, pd.output_logical - start, pd.input_logical - start, layout_.size()))
        throw RunError(fmt::format("slave {}: the process data is not the CiA 402 mapping the master wrote", i + 1));
    }
    std::uint16_t reference = 0;
    if (s_.master.dc) {
      const master::DcResult dc = master::configure_dc(m, master::DcOptions{1000});
      reference = dc.reference_station;
      for (std::size_t i = 0; i < network_.size(); ++i)
        if (m.slaves()[i].dc_supported) master::write_dc_sync_parameters(m, i, s_.master.cycle, notes);
      if (dc.dc_slaves) master::activate_sync0(m, static_cast<std::uint32_t>(s_.master.cycle), 0, 10'000'000);
      say(fmt::format("DC: reference 0x{:04X}, {} slaves, SYNC0 every {} us", dc.reference_station, dc.dc_slaves, s_.master.cycle / 1000));
    }
    for (const std::string& n : notes) say("note: " + n);
    if (!m.request_state(master::AlState::SafeOp)) throw RunError("not every slave reached Safe-Op:" + al_summary());
    say("Safe-Op");
    task_ = std::make_unique<master::CyclicTask>(m.transport(), layout_, network_.size(), s_.master.cycle, reference);
    // Half a cycle for the reply, so a lost frame costs its own cycle and not the next one too.
    task_->set_reply_timeout(s_.master.cycle / 2);
    task_->on_outputs([this](std::span<std::uint8_t> image) {
      for (AxisControl& a : axes_) a.outputs(image, clock_->now());
    });
    task_->on_inputs([this](std::span<std::uint8_t> image) {
      for (AxisControl& a : axes_) a.inputs(image);
    });
    // Op is requested after some cycles in Safe-Op, so the drives see valid outputs first.
    op_after_cycle_ = target == AlTarget::op ? kSafeOpCycles : 0;
    say(fmt::format("cyclic frames every {} us", s_.master.cycle / 1000));
  }

  void sdo_write(const SdoWriteAction& w) {
    const auto i = static_cast<std::size_t>(w.slave - 1);
    const od::EntryDesc* entry = network_.firmware(i).objects().dictionary().find(w.index, w.subindex);
    if (!entry) throw RunError(fmt::format("sdo_write: slave {} ({}) has no object {:04X}h:{:02X}", w.slave, network_.profile(i).id, w.index, w.subindex));
    std::array<std::uint8_t, 8> bytes{};
    const std::size_t n = std::clamp<std::size_t>(entry->value_bytes, 1, 8);
    for (std::size_t b = 0; b < n; ++b) bytes[b] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(w.value) >> (8 * b));
    try {
      master("sdo_write").sdo(i).download(w.index, w.subindex, std::span<const std::uint8_t>(bytes).first(n));
      say(fmt::format("slave {}: {:04X}h:{:02X} := {}", w.slave, w.index, w.subindex, w.value));
    } catch (const master::SdoAbort& e) {
      say(fmt::format("slave {}: {:04X}h:{:02X} := {} aborted: {}", w.slave, w.index, w.subindex, w.value, e.what()));
    }
  }

  AxisControl& axis(int slave, std::string_view what) {
    master(what);
    AxisControl& a = axes_[static_cast<std::size_t>(slave - 1)];
    if (!a.mapped())
      throw RunError(fmt::format("{}: slave {} has no CiA 402 process data yet (the master maps it on the way to Safe-Op)", what, slave));
    return a;
  }

  void perform(const Step& st) {
    current_step_ = &st;
    const Nanos now = clock_->now();
    std::visit([&](const auto& a) { act(a, now); }, st.action);
  }

  void act(const StateAction& a, Nanos) {
    const auto target = static_cast<master::AlState>(a.state);
    say(a.slave ? fmt::format("slave {}: request {}", a.slave, state_name(static_cast<std::uint16_t>(a.state)))
                : fmt::format("request {}", state_name(static_cast<std::uint16_t>(a.state))));
    if (task_ && a.slave == 0) {
      task_->request_state(target);
    } else if (!task_ && (a.state == AlTarget::safeop || a.state == AlTarget::op) && a.slave == 0) {
      go_up_to(a.state);
    } else if (a.slave) {
      master("state").request_state(static_cast<std::size_t>(a.slave - 1), target);
    } else {
      master("state").request_state(target);
    }
  }
  void act(const SdoWriteAction& a, Nanos) { sdo_write(a); }
  void act(const SdoReadAction& a, Nanos now) {
    const auto i = static_cast<std::size_t>(a.slave - 1);
    const od::EntryDesc* entry = network_.firmware(i).objects().dictionary().find(a.index, a.subindex);
    if (!entry) throw RunError(fmt::format("sdo_read: slave {} ({}) has no object {:04X}h:{:02X}", a.slave, network_.profile(i).id, a.index, a.subindex));
    std::string outcome;
    std::optional<std::int64_t> value;
    try {
      const std::vector<std::uint8_t> bytes = master("sdo_read").sdo(i).upload(a.index, a.subindex);
      value = od::entry_integer(*entry, bytes);
      outcome = fmt::format("{}", *value);
    } catch (const master::SdoAbort& e) {
      outcome = fmt::format("aborted: {}", e.what());
    }
    say(fmt::format("slave {}: {:04X}h:{:02X} = {}", a.slave, a.index, a.subindex, outcome));
    if (!a.expect) return;
    ExpectationResult r;
    r.name = current_step_->name.empty() ? fmt::format("sdo_read {:04X}h:{:02X} (line {})", a.index, a.subindex, current_step_->line)
                                         : current_step_->name;
    r.line = current_step_->line;
    r.decided = true;
    r.time = now;
    r.passed = value && holds(*a.expect, *value);
    r.message = r.passed ? fmt::format("read {}", outcome) : fmt::format("read {}, expected {}", outcome, describe(*a.expect));
    step_results_.push_back(std::move(r));
  }
  void act(const ControlwordAction& a, Nanos) {
    axis(a.slave, "controlword").set_controlword(a.value);
    say(fmt::format("slave {}: 6040h := 0x{:04X}", a.slave, a.value));
  }
  void act(const ModeAction& a, Nanos) {
    axis(a.slave, "mode").set_mode(a.mode);
    say(fmt::format("slave {}: 6060h := {}", a.slave, a.mode));
  }
  void act(const EnableAction& a, Nanos) {
    axis(a.slave, "enable").enable(a.mode);
    say(fmt::format("slave {}: enable in mode {}", a.slave, a.mode));
  }
  void act(const DisableAction& a, Nanos) {
    axis(a.slave, "disable").disable();
    say(fmt::format("slave {}: disable", a.slave));
  }
  void act(const TargetAction& a, Nanos) {
    axis(a.slave, "target").set_target(a);
    events_.set_point_given(a.slave);
    say(fmt::format("slave {}: target{}{}{}", a.slave, a.position ? fmt::format(" position {}", *a.position) : "",
                    a.velocity ? fmt::format(" velocity {}", *a.velocity) : "", a.torque ? fmt::format(" torque {}", *a.torque) : ""));
  }
  void act(const MotionAction& a, Nanos now) {
    axis(a.slave, "motion").start_motion(a, now);
    events_.set_point_given(a.slave);
    say(a.shape == MotionAction::Shape::ramp ? fmt::format("slave {}: ramp to {} at {}/s", a.slave, a.position, a.velocity)
                                             : fmt::format("slave {}: sine {} at {} Hz", a.slave, a.amplitude, a.frequency_hz));
  }
  void act(const FaultAction& a, Nanos now) {
    const int id = faults_.inject(a.fault, now);
    if (!a.id.empty()) fault_ids_[a.id] = id;
    say("fault: " + fault::describe(a.fault));
  }
  void act(const ClearFaultAction& a, Nanos now) {
    if (a.id.empty()) {
      faults_.clear_all(now);
      say("every fault cleared");
      return;
    }
    const auto it = fault_ids_.find(a.id);
    if (it == fault_ids_.end() || !faults_.clear(it->second, now)) {
      say(fmt::format("clear_fault {}: not active", a.id));
      return;
    }
    say(fmt::format("fault {} cleared", a.id));
  }
  void act(const SignalAction& a, Nanos) {
    signal(a.signal, current_step_ != nullptr ? current_step_->line : 0).write(a.value);
    say(fmt::format("signal {} = {}", a.signal, a.value));
  }
  void act(const AcknowledgeAction& a, Nanos) {
    master("acknowledge").read_al_status(static_cast<std::size_t>(a.slave - 1));  // the acknowledge repeats the current state
    master_->acknowledge_error(static_cast<std::size_t>(a.slave - 1));
    say(fmt::format("slave {}: AL error acknowledged", a.slave));
  }

  void run_due_steps() {
    for (std::size_t k = 0; k < s_.steps.size(); ++k) {
      if (ran_[k]) continue;
      const auto t = events_.resolve(s_.steps[k].when);
      if (!t || *t > clock_->now()) continue;
      ran_[k] = true;
      perform(s_.steps[k]);
      events_.step_ran(s_.steps[k].name, clock_->now());
    }
  }

  std::int64_t probe(const Probe& p) {
    switch (p.kind) {
      case Probe::Kind::object: {
        const drive::ObjectRef<std::int64_t> ref(network_.firmware(static_cast<std::size_t>(p.slave - 1)).objects(), p.index, p.subindex);
        return ref.get();
      }
      case Probe::Kind::al_state: return peek16(static_cast<std::size_t>(p.slave - 1), kAlStatus);
      case Probe::Kind::al_status_code: return peek16(static_cast<std::size_t>(p.slave - 1), kAlStatusCode);
      case Probe::Kind::esc_register: {
        esc::Esc& e = network_.esc(static_cast<std::size_t>(p.slave - 1));
        std::uint32_t v = 0;
        for (std::uint8_t b = 0; b < p.size; ++b) v |= static_cast<std::uint32_t>(e.peek(static_cast<std::uint16_t>(p.index + b))) << (8 * b);
        return v;
      }
      case Probe::Kind::master_wrong_wkc: return task_ ? static_cast<std::int64_t>(task_->stats().wrong_wkc) : 0;
      case Probe::Kind::master_lost_frames: return task_ ? static_cast<std::int64_t>(task_->stats().lost_frames) : 0;
      case Probe::Kind::signal: return signals_.at(p.signal).read();
    }
    return 0;
  }

  std::int64_t object(std::size_t i, std::uint16_t index) {
    return drive::ObjectRef<std::int64_t>(network_.firmware(i).objects(), index).get();
  }

  // Real time: each host stall the line's loop recorded, in the log and the report.
  void note_stalls() {
    const runtime::HostStalls& stalls = loop_counters_->stalls;
    for (const std::uint64_t count = stalls.count(); stalls_seen_ < count;) {
      const std::optional<runtime::HostStall> s = stalls.get(++stalls_seen_);
      if (!s) continue;
      const std::string text = runtime::describe(*s);
      say(text);
      if (result_.stalls.size() < ScenarioResult::kMaxStallNotes) result_.stalls.push_back({s->time, s->length, text});
    }
  }
  // " after a host stall of 12.3 ms" for a fault seen now, if one came just before.
  std::string after_stall() const {
    return loop_counters_ != nullptr ? runtime::after_stall(loop_counters_->stalls.just_before(clock_->now())) : std::string();
  }

  void observe() {
    const Nanos now = clock_->now();
    if (loop_counters_ != nullptr) note_stalls();
    std::uint16_t common = 0;
    bool same = true;
    for (std::size_t i = 0; i < network_.size(); ++i) {
      const std::uint16_t al = peek16(i, kAlStatus) & 0x0F;
      if (i == 0) common = al;
      same = same && al == common;
      if (al != last_al_[i]) {
        const std::uint16_t code = peek16(i, kAlStatusCode);
        say(fmt::format("slave {}: {} (AL status code 0x{:04X}){}", i + 1, state_name(al), code, code != 0 ? after_stall() : ""));
        last_al_[i] = al;
      }
      if (is_drive(i)) {
        const auto sw = static_cast<std::uint16_t>(object(i, 0x6041));
        const auto before = last_status_[i];
        events_.statusword(static_cast<int>(i + 1), sw, now);
        if ((sw & 0x0008) && !(before & 0x0008))
          say(fmt::format("slave {}: Fault, 603Fh 0x{:04X}{}", i + 1, static_cast<std::uint16_t>(object(i, 0x603F)), after_stall()));
        if ((sw & 0x006F) == 0x0027 && (before & 0x006F) != 0x0027) say(fmt::format("slave {}: Operation enabled", i + 1));
        last_status_[i] = sw;
      }
    }
    if (same && (common == 2 || common == 4 || common == 8)) events_.all_in_state(static_cast<AlTarget>(common), now);
    for (ExpectationCheck& c : checks_) {
      const bool open = !c.result().decided;
      c.check(now, probe(c.expectation().probe), events_);
      if (open && c.result().decided && o_.decided) o_.decided(c.result());
    }
    if (trace_ && now >= next_trace_) {
      for (std::size_t i = 0; i < network_.size(); ++i) {
        TraceRow r;
        r.time = now;
        r.slave = static_cast<int>(i + 1);
        r.al_status = peek16(i, kAlStatus);
        r.al_status_code = peek16(i, kAlStatusCode);
        r.station = peek16(i, ecat::reg::kStationAddress);
        if (is_drive(i)) {
          r.statusword = static_cast<std::uint16_t>(object(i, 0x6041));
          r.controlword = static_cast<std::uint16_t>(object(i, 0x6040));
          r.mode = object(i, 0x6061);
          r.position = object(i, 0x6064);
          r.velocity = object(i, 0x606C);
          r.torque = object(i, 0x6077);
          r.following_error = object(i, 0x60F4);
          r.error_code = static_cast<std::uint16_t>(object(i, 0x603F));
        }
        trace_->write(r);
      }
      next_trace_ = s_.trace_period > 0 ? now + s_.trace_period : now;
    }
  }

  void loop() {
    last_al_.assign(network_.size(), 0);
    last_status_.assign(network_.size(), 0);
    Nanos next_cycle = clock_->now();
    Nanos next_second = (clock_->now() / 1'000'000'000 + 1) * 1'000'000'000;
    while (clock_->now() < s_.duration) {
      run_due_steps();
      faults_.tick(clock_->now());
      if (task_) {
        task_->run_cycle();
        if (op_after_cycle_ && task_->stats().cycles >= op_after_cycle_) {
          task_->request_state(master::AlState::Op);
          say("request Op");
          op_after_cycle_ = 0;
        }
      }
      observe();
      if (clock_->now() >= next_second) {
        say(fmt::format("{} s:{} {} cycles, {} wrong working counters", clock_->now() / 1'000'000'000, al_summary(),
                        task_ ? task_->stats().cycles : 0, task_ ? task_->stats().wrong_wkc : 0));
        next_second += 1'000'000'000;
        if (o_.progress) o_.progress(clock_->now());
      }
      next_cycle += s_.master.cycle;
      // A cycle that ran late (a mailbox step) is not made up: the next starts on the grid.
      if (next_cycle <= clock_->now())
        next_cycle += ((clock_->now() - next_cycle) / s_.master.cycle + 1) * s_.master.cycle;
      if (master_) master_->transport().idle_until(std::min(next_cycle, s_.duration));
      else wire_->serve_until(std::min(next_cycle, s_.duration));
    }
    say(fmt::format("end:{} {} cycles, {} wrong working counters, {} lost frames", al_summary(), task_ ? task_->stats().cycles : 0,
                    task_ ? task_->stats().wrong_wkc : 0, task_ ? task_->stats().lost_frames : 0));
  }

  const Scenario& s_;
  const RunOptions& o_;
  std::vector<std::string> ids_;
  std::unique_ptr<Clock> clock_;
  network::Network network_;
  fault::WireImpairment impairment_;
  std::unique_ptr<link::RawSocketLink> line_link_, master_link_;  // real time only
  std::unique_ptr<ScenarioWire> wire_;
  std::unique_ptr<LineTap> tap_;  // after wire_: ends before the wire it taps
  fault::FaultInjector faults_;
  std::unique_ptr<master::Master> master_;                      // null: an external master
  EventLog events_;
  std::vector<AxisControl> axes_;
  std::vector<bool> ran_;
  std::vector<ExpectationCheck> checks_;
  std::vector<ExpectationResult> step_results_;  // sdo_read steps with a condition
  const Step* current_step_ = nullptr;
  std::map<std::string, int> fault_ids_;
  std::map<std::string, network::SignalAccess> signals_;
  master::ProcessImageLayout layout_;
  std::unique_ptr<master::CyclicTask> task_;
  std::unique_ptr<PcapngWriter> capture_;
  std::unique_ptr<TraceWriter> trace_;
  Nanos next_trace_ = 0;
  std::uint64_t op_after_cycle_ = 0;
  std::vector<std::uint16_t> last_al_, last_status_;
  const runtime::LoopCounters* loop_counters_ = nullptr;  // real time: the line's loop (host stalls)
  std::uint64_t stalls_seen_ = 0;
  ScenarioResult result_;
};

}  // namespace

ScenarioResult run_scenario(const Scenario& scenario, const RunOptions& options) {
  return Run(scenario, options).go();
}

}  // namespace vdrive::scenario
