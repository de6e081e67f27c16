#include "vdrive/cli/telemetry_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "ethercat/slave_ref.hpp"
#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/fault_inject_options.hpp"
#include "vdrive/cli/slave_option.hpp"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/runtime/line_status.hpp"
#include "vdrive/runtime/stop_signal.hpp"
#include "vdrive/telemetry/sampler.hpp"
#include "vdrive/telemetry/telemetry_client.hpp"
#include "vdrive/telemetry/topics.hpp"

namespace vdrive::cli {
namespace {

constexpr const char* kAxisHeader =
    "time_ns,slave,al_state,al_status_code,statusword,controlword,mode,position,velocity,torque,following_error,error_code,"
    "winding_temperature_c,housing_temperature_c,station";
constexpr const char* kEventHeader = "time_ns,slave,kind,value,previous,text";
constexpr Nanos kViewRefresh = 100'000'000;  // live view: 10 updates per second

std::unique_ptr<telemetry::TelemetryClient> open_client(int domain) {
  try {
    return std::make_unique<telemetry::TelemetryClient>(domain);
  } catch (const telemetry::DdsError& e) {
    throw CliError(kExitFailure, e.what());
  }
}

std::string fmt_temp(double c) { return std::isnan(c) ? std::string() : fmt::format("{:.2f}", c); }

std::string csv_text(std::string s) {
  for (char& c : s)
    if (c == '"' || c == '\n') c = '\'';
  return '"' + s + '"';
}

}  // namespace

std::string telemetry_axis_line(const telemetry::AxisSample& a) {
  return fmt::format("t={:.3f}s {} {}{} sw=0x{:04X} cw=0x{:04X} mode={} pos={} vel={} torque={} ferr={} err=0x{:04X}{}",
                     static_cast<double>(a.time) * 1e-9, ecat::slave_label(a.slave - 1u, a.station, ""),
                     runtime::al_state_name(a.al_state), (a.al_state & 0x10) ? "+ERR" : "",
                     a.statusword, a.controlword, a.mode, a.position, a.velocity, a.torque, a.following_error, a.error_code,
                     std::isnan(a.winding_c) ? std::string() : fmt::format(" winding={:.1f}C", a.winding_c));
}

int telemetry_domain(std::optional<int> option) {
  try {
    return telemetry::resolve_domain(option);
  } catch (const telemetry::DomainError& e) {
    throw CliError(kExitBadArguments, e.what());
  }
}

namespace {

struct WatchOptions {
  std::optional<int> domain;
  std::string csv, events_csv;
  double duration_s = 0.0;  // 0: until Ctrl-C (or --count)
  std::uint64_t count = 0;  // 0: no limit
  std::string slave;        // "": all; a position or a station address (ecat::parse_slave_ref)
  bool quiet = false;
};

// --slave: a position matches the samples' cable order, an address their station address. Events
// carry the position only: an address finds it in the samples heard so far.
class SlaveFilter {
public:
  explicit SlaveFilter(const std::string& text) {
    if (!text.empty()) ref_ = ecat::parse_slave_ref(text);
  }
  bool keeps(std::uint16_t slave, std::uint16_t station) {
    if (!ref_) return true;
    if (!ref_->is_address()) return slave == ref_->value;
    if (station == ref_->value) position_ = slave;
    return station == ref_->value;
  }
  // An event of `slave` (0: the line, always kept).
  bool keeps_event(std::uint16_t slave) const {
    if (!ref_ || slave == 0) return true;
    return ref_->is_address() ? position_ == slave : slave == ref_->value;
  }

private:
  std::optional<ecat::SlaveRef> ref_;
  std::uint16_t position_ = 0;  // the address's position, once a sample showed it
};

// A subscriber that hears nothing says so after this long, and fails at the end.
constexpr auto kNoPublisherHint = std::chrono::seconds(5);
constexpr const char* kNoPublisherWhy =
    "no `vdrive run --telemetry` (or `scenario run --telemetry`) publishes there. Check --domain; a run "
    "started with `ip netns exec` publishes inside that namespace, out of reach: serve with "
    "`vdrive run --netns NAME --iface IF --telemetry` instead (docs/telemetry.md)";

void watch(const WatchOptions& o) {
  const int domain = telemetry_domain(o.domain);
  std::ofstream csv, events;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    if (!csv) throw CliError(kExitFailure, fmt::format("--csv {}: cannot create the file", o.csv));
    csv << kAxisHeader << '\n';
  }
  if (!o.events_csv.empty()) {
    events.open(o.events_csv);
    if (!events) throw CliError(kExitFailure, fmt::format("--events-csv {}: cannot create the file", o.events_csv));
    events << kEventHeader << '\n';
  }
  const std::unique_ptr<telemetry::TelemetryClient> client = open_client(domain);
  const bool tty = ::isatty(STDOUT_FILENO) == 1;
  const bool view = !o.quiet && (o.csv.empty() || tty);
  if (!o.quiet) fmt::print(stderr, "vdrive telemetry: domain {}, {} (Ctrl-C stops)\n", domain, telemetry::topic_name(telemetry::Topic::axis_state));

  std::map<int, telemetry::AxisSample> last_axis;
  std::map<int, telemetry::BusSample> last_bus;
  std::map<int, Nanos> last_printed;  // plain lines: per axis, at most one per kViewRefresh
  std::uint64_t rows = 0;
  SlaveFilter filter(o.slave);
  int drawn = 0;  // lines of the live block on the terminal
  const auto started = std::chrono::steady_clock::now();
  auto next_draw = started;
  std::atomic<bool>& stop = runtime::stop_on_termination_signals();

  telemetry::TelemetryHandlers h;
  bool heard = false;  // anything from any publisher, whatever the filters keep
  h.axis = [&](const telemetry::AxisSample& a) {
    heard = true;
    if (!filter.keeps(a.slave, a.station)) return;
    if (o.count != 0 && rows >= o.count) return;
    ++rows;
    if (csv.is_open()) {
      csv << a.time << ',' << a.slave << ',' << a.al_state << ',' << a.al_status_code << ',' << a.statusword << ','
          << a.controlword << ',' << int{a.mode} << ',' << a.position << ',' << a.velocity << ',' << a.torque << ','
          << a.following_error << ',' << a.error_code << ',' << fmt_temp(a.winding_c) << ',' << fmt_temp(a.housing_c) << ','
          << a.station << '\n';
    }
    last_axis[a.slave] = a;
    if (view && !tty) {
      auto [it, fresh] = last_printed.try_emplace(a.slave, a.time);
      if (fresh || a.time - it->second >= kViewRefresh) {
        it->second = a.time;
        fmt::print("{}\n", telemetry_axis_line(a));
        std::fflush(stdout);
      }
    }
  };
  h.bus = [&](const telemetry::BusSample& b) {
    heard = true;
    if (filter.keeps(b.slave, b.station)) last_bus[b.slave] = b;
  };
  h.event = [&](const telemetry::Event& e) {
    heard = true;
    if (!filter.keeps_event(e.slave)) return;
    if (events.is_open()) events << e.time << ',' << e.slave << ',' << e.kind << ',' << e.value << ',' << e.previous << ',' << csv_text(e.text) << '\n';
    if (!o.quiet && !tty) fmt::print("event t={:.3f}s slave {} {}: {}\n", static_cast<double>(e.time) * 1e-9, e.slave, e.kind, e.text);
    if (!o.quiet && tty) fmt::print(stderr, "\nevent t={:.3f}s slave {} {}: {}\n", static_cast<double>(e.time) * 1e-9, e.slave, e.kind, e.text), drawn = 0;
  };

  bool hinted = false;
  for (;;) {
    if (stop.load()) break;
    if (o.count != 0 && rows >= o.count) break;
    const auto now = std::chrono::steady_clock::now();
    if (!heard && !hinted && now - started >= kNoPublisherHint) {
      hinted = true;
      fmt::print(stderr, "vdrive telemetry: nothing heard in domain {} after {} s: {}\n", domain,
                 std::chrono::duration_cast<std::chrono::seconds>(kNoPublisherHint).count(), kNoPublisherWhy);
    }
    if (o.duration_s > 0 && now - started >= std::chrono::duration<double>(o.duration_s)) break;
    client->poll(50'000'000, h);
    if (view && tty && std::chrono::steady_clock::now() >= next_draw) {
      next_draw = std::chrono::steady_clock::now() + std::chrono::nanoseconds(kViewRefresh);
      if (drawn > 0) fmt::print("\x1b[{}F", drawn);  // back to the block's first line
      drawn = 0;
      for (const auto& [slave, a] : last_axis) fmt::print("\x1b[2K{}\n", telemetry_axis_line(a)), ++drawn;
      for (const auto& [slave, b] : last_bus) {
        fmt::print("\x1b[2K  bus {}: frames in {} out {} dropped {}, rx errors {}, turnaround mean {} ns max {} ns, samples dropped {}, "
                   "host stalls {}\n",
                   ecat::slave_label(slave - 1u, b.station, ""), b.frames_in, b.frames_out, b.frames_dropped, b.rx_errors, b.turnaround_mean, b.turnaround_max, b.samples_dropped,
                   b.host_stalls);
        ++drawn;
      }
      std::fflush(stdout);
    }
  }
  if (!o.quiet) fmt::print(stderr, "vdrive telemetry: {} axis sample(s)\n", rows);
  if (!heard)
    throw CliError(kExitFailure, fmt::format("no telemetry heard in domain {} in {:.1f} s: {}", domain,
                                             std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                                             kNoPublisherWhy));
}

// The control side: one request, its reply, the exit code a refusal maps to.
struct DdsTarget {
  std::optional<int> domain;
  double timeout_s = 5.0;
};

control::ControlReply dds_request(const DdsTarget& t, const nlohmann::json& req) {
  const int domain = telemetry_domain(t.domain);
  const std::unique_ptr<telemetry::TelemetryClient> client = open_client(domain);
  std::optional<control::ControlReply> reply;
  try {
    reply = client->call(req.dump(), static_cast<Nanos>(t.timeout_s * 1e9));
  } catch (const control::ProtocolError& e) {
    throw CliError(kExitFailure, fmt::format("garbled reply on {}: {}", telemetry::topic_name(telemetry::Topic::control_reply), e.what()));
  }
  if (!reply)
    throw CliError(kExitFailure, fmt::format("no vdrive answered on {} in DDS domain {} within {:g} s (is vdrive run --telemetry running there?)",
                                             telemetry::topic_name(telemetry::Topic::control_request), domain, t.timeout_s));
  switch (reply->status) {
    case control::ControlReply::Status::ok: return *reply;
    case control::ControlReply::Status::bad_request: throw CliError(kExitBadArguments, reply->error);
    case control::ControlReply::Status::denied: throw CliError(kExitNotPermitted, reply->error);
    case control::ControlReply::Status::failed: break;
  }
  throw CliError(kExitFailure, reply->error);
}

void dds_inject(const DdsTarget& t, const FaultInjectOptions& o) {
  const control::ControlReply r = dds_request(t, {{"op", "inject"}, {"fault", fault_json(o)}});
  if (r.id != 0) fmt::print("fault {} injected\n", r.id);
  else fmt::print("one-shot fault injected\n");
}

void dds_clear(const DdsTarget& t, const std::string& what) {
  if (what == "all") {
    const control::ControlReply r = dds_request(t, {{"op", "clear_all"}});
    fmt::print("{} fault(s) cleared\n", r.cleared);
    return;
  }
  int id = 0;
  try {
    std::size_t used = 0;
    id = std::stoi(what, &used);
    if (used != what.size() || id < 1) throw std::invalid_argument(what);
  } catch (const std::exception&) {
    throw CliError(kExitBadArguments, fmt::format("telemetry clear '{}': expected a fault id (1, 2, ...) or 'all'", what));
  }
  dds_request(t, {{"op", "clear"}, {"id", id}});
  fmt::print("fault {} cleared\n", id);
}

void add_dds_target(CLI::App* cmd, DdsTarget& t) {
  cmd->add_option("--domain", t.domain, "DDS domain id 0..232 (default $ROS_DOMAIN_ID, else 0)");
  cmd->add_option("--timeout", t.timeout_s, "Seconds to wait for a vdrive to answer (default 5)")->check(CLI::Range(0.1, 3600.0));
}

}  // namespace

void add_telemetry_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("telemetry", "Live view or CSV of the DDS telemetry of vdrive run --telemetry; control requests");
  cmd->require_subcommand(0, 1);
  cmd->footer("Examples:\n"
              "  vdrive telemetry                                  # live view of every axis in domain $ROS_DOMAIN_ID or 0\n"
              "  vdrive telemetry --csv axes.csv --duration 10 -q && vdrive plot axes.csv\n"
              "  vdrive telemetry inject encoder_error --slave 1   # through rt/vdrive/control_request\n"
              "  vdrive telemetry plant-set --slave 2 --external-load 0.5\n"
              "Exit 1 also when no vdrive answers a request within --timeout.");
  auto w = std::make_shared<WatchOptions>();
  cmd->add_option("--domain", w->domain, "DDS domain id 0..232 (default $ROS_DOMAIN_ID, else 0)");
  cmd->add_option("--csv", w->csv, "Record per-axis samples to FILE (the scenario trace's columns, plus temperatures)");
  cmd->add_option("--events-csv", w->events_csv, "Record events to FILE (time_ns,slave,kind,value,previous,text)");
  cmd->add_option("--duration", w->duration_s, "Stop after S seconds (default: until Ctrl-C)")->check(CLI::Range(0.0, 1e9));
  cmd->add_option("--count", w->count, "Stop after N axis samples");
  cmd->add_option("--slave", w->slave, "Only this slave: its position (1 = first) or station address (0x1002)")
      ->check(slave_ref_validator());
  cmd->add_flag("--quiet,-q", w->quiet, "No live view (with --csv: record only)");
  cmd->callback([cmd, w] {
    if (cmd->get_subcommands().empty()) watch(*w);
  });

  auto t = std::make_shared<DdsTarget>();
  auto o = std::make_shared<FaultInjectOptions>();
  CLI::App* inj = cmd->add_subcommand("inject", "Start a fault through the control topic (kinds: vdrive fault kinds)");
  add_dds_target(inj, *t);
  add_fault_inject_options(inj, *o);
  inj->callback([t, o] { dds_inject(*t, *o); });

  auto what = std::make_shared<std::string>();
  CLI::App* clr = cmd->add_subcommand("clear", "End a fault by its id, or 'all'");
  add_dds_target(clr, *t);
  clr->add_option("id", *what, "Fault id, or all")->required();
  clr->callback([t, what] { dds_clear(*t, *what); });

  auto slave = std::make_shared<std::string>();
  auto load = std::make_shared<double>(0.0);
  CLI::App* ps = cmd->add_subcommand("plant-set", "Change a plant parameter at run time: the external load on an axis");
  add_dds_target(ps, *t);
  ps->add_option("--slave", *slave, "The slave: its position (1 = first) or station address (0x1002)")
      ->required()
      ->check(slave_ref_validator());
  ps->add_option("--external-load", *load, "External force/torque on the load, N or N m (0: none)")->required();
  ps->callback([t, slave, load] {
    dds_request(*t, {{"op", "plant_set"}, {"slave", slave_json(*slave)}, {"external_load", *load}});
    fmt::print("slave {}: external load {:g}\n", *slave, *load);
  });
}

void add_run_telemetry_options(CLI::App* run, RunTelemetryOptions& o) {
  run->add_flag("--telemetry", o.enabled, "Publish DDS telemetry and take control requests (docs/telemetry.md)");
  run->add_option("--telemetry-rate", o.rate_hz, "Telemetry samples per second per axis (default 100, at most 8000)")
      ->check(CLI::Range(0.001, telemetry::kMaxRateHz));
  run->add_option("--domain", o.domain, "DDS domain id 0..232 for --telemetry (default $ROS_DOMAIN_ID, else 0)");
}

std::unique_ptr<telemetry::LineTelemetry> start_run_telemetry(const RunTelemetryOptions& o, network::Network& network, link::Link& served,
                                                              const Clock& clock, const runtime::LoopCounters& counters,
                                                              control::FaultService* faults, std::function<void()> wake) {
  if (!o.enabled) return nullptr;
  const int domain = telemetry_domain(o.domain);
  try {
    auto t = std::make_unique<telemetry::LineTelemetry>(network, served, clock, counters, faults,
                                                        telemetry::LineTelemetryOptions{o.rate_hz, domain, o.place, o.requests}, std::move(wake));
    spdlog::info("telemetry: DDS domain {}, {:g} Hz, topics rt/vdrive/{{axis_state,bus_state,events{}", domain, o.rate_hz,
                 o.requests.take_requests ? ",control_request,control_reply}" : "} (part 1 takes the requests)");
    return t;
  } catch (const telemetry::DdsError& e) {
    throw CliError(kExitFailure, fmt::format("--telemetry: {}", e.what()));
  }
}

}  // namespace vdrive::cli
