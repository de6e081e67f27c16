#include "vdrive/cli/scenario_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/telemetry_command.hpp"
#include "vdrive/cli/web_option.hpp"
#include "vdrive/telemetry/loop_services.hpp"
#include "vdrive/web/line_record.hpp"
#include "vdrive/control/fault_service.hpp"
#include "vdrive/cli/veth_pair.hpp"
#include "vdrive/link/link_error.hpp"
#include "vdrive/runtime/host_stalls.hpp"
#include "vdrive/scenario/junit_writer.hpp"
#include "vdrive/scenario/scenario_loader.hpp"
#include "vdrive/scenario/scenario_runner.hpp"

namespace vdrive::cli {
namespace {

// " (after a host stall of 12.3 ms)" when a real-time run's expectation failed at `time` soon
// after a stall: the user can tell the host from the drive. Not for one decided when the run
// ended (it was still open: nothing failed at that moment).
std::string stall_before(const scenario::ScenarioResult& r, Nanos time) {
  if (time >= r.ended) return "";
  for (auto it = r.stalls.rbegin(); it != r.stalls.rend(); ++it)
    if (it->time <= time && time - it->time <= runtime::kStallAftermath) return fmt::format(" (after a host stall of {})", runtime::stall_ms(it->length));
  return "";
}

struct ScenarioOptions {
  std::string path;
  std::string junit, trace, pcap;
  std::uint64_t seed = 0;
  bool seed_given = false;
  bool verbose = false;
  bool veth = false;          // real time: the built-in master over a veth pair made for the run
  std::string iface;          // real time: an external master on this interface
  RunTelemetryOptions telemetry;  // real time: DDS telemetry of the line (docs/telemetry.md)
  std::string web;                // real time: the live page (docs/web.md)
};

// What a real-time run serves beside the line: --telemetry (DDS) and --web (the live page), with a
// fault service of their own for the requests they carry (the scenario's own faults go through the
// runner's injector; wire faults need the runner's wire and are refused here).
class ScenarioTaps final : public scenario::LineTap {
public:
  ScenarioTaps(const ScenarioOptions& o, network::Network& network, link::Link& served, const Clock& clock,
               const runtime::LoopCounters& counters)
      : served_(served), faults_(network, nullptr, nullptr),
        telemetry_(o.telemetry.enabled ? start_run_telemetry(o.telemetry, network, served, clock, counters, &faults_, [] {}) : nullptr),
        page_(start_web(o.web, network, clock, counters, &faults_, "scenario", o.veth ? "veth" : o.iface, nullptr)),
        services_(telemetry_ ? &telemetry_->service() : static_cast<runtime::LoopService*>(&faults_),
                  page_ ? &page_->service() : nullptr) {}
  ~ScenarioTaps() override {
    if (telemetry_) std::fprintf(stderr, "telemetry: %llu samples published, %llu dropped\n",
                                 static_cast<unsigned long long>(telemetry_->published()),
                                 static_cast<unsigned long long>(telemetry_->dropped()));
  }
  link::Link& link() override { return telemetry_ ? telemetry_->link() : served_; }
  runtime::LoopService& service() override { return services_; }
  web::WebServer* page() { return page_.get(); }

private:
  link::Link& served_;
  control::FaultService faults_;
  std::unique_ptr<telemetry::LineTelemetry> telemetry_;
  std::unique_ptr<web::WebServer> page_;
  telemetry::LoopServices services_;
};

// The scenario as the page shows it before it starts: every expectation open.
web::ScenarioView scenario_view(const scenario::Scenario& s) {
  web::ScenarioView v;
  v.name = s.name;
  v.duration = s.duration;
  for (const scenario::Expectation& e : s.expectations) v.expectations.push_back({e.line, e.name, "open", ""});
  return v;
}

// OUT.csv -> OUT-<name>.csv when several scenarios share one option.
std::string per_scenario(const std::string& path, const std::string& name, bool several) {
  if (path.empty() || !several) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + "-" + name + p.extension().string())).string();
}

void run(const ScenarioOptions& o) {
  std::vector<scenario::Scenario> scenarios;
  try {
    for (const std::string& f : scenario::scenario_files(o.path)) scenarios.push_back(scenario::load_scenario_file(f));
  } catch (const scenario::ScenarioError& e) {
    throw CliError(kExitBadArguments, e.what());
  }
  const bool several = scenarios.size() > 1;
  if (o.veth && !o.iface.empty()) throw CliError(kExitBadArguments, "--veth and --iface exclude each other");
  if (o.telemetry.enabled && !o.veth && o.iface.empty())
    throw CliError(kExitBadArguments, "--telemetry needs a real-time run (--veth or --iface): virtual time runs faster than any subscriber");
  if (!o.web.empty() && !o.veth && o.iface.empty())
    throw CliError(kExitBadArguments, "--web needs a real-time run (--veth or --iface): virtual time runs faster than any page");
  if (o.telemetry.enabled) telemetry_domain(o.telemetry.domain);  // a bad domain is named before anything starts
  // One pair for the whole run; names unique per process so parallel runs do not collide.
  std::unique_ptr<VethPair> veth;
  if (o.veth) veth = std::make_unique<VethPair>(fmt::format("vds{}m", ::getpid()), fmt::format("vds{}l", ::getpid()));
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  std::vector<scenario::ScenarioResult> results;
  std::size_t failed = 0;
  for (const scenario::Scenario& s : scenarios) {
    scenario::RunOptions ro;
    ro.trace_path = per_scenario(o.trace, s.name, several);
    ro.pcap_path = per_scenario(o.pcap, s.name, several);
    if (o.seed_given) ro.seed = o.seed;
    if (veth) {
      ro.master_interface = veth->master_end();
      ro.line_interface = veth->slave_end();
    } else if (!o.iface.empty()) {
      ro.line_interface = o.iface;
    }
    // The page of this run, once the runner has built the line (its log and verdicts go there too).
    web::WebServer* page = nullptr;
    if (o.telemetry.enabled || !o.web.empty()) {
      ro.line_tap = [&o, &page, &s](network::Network& network, link::Link& served, const Clock& clock, const runtime::LoopCounters& counters) {
        auto taps = std::make_unique<ScenarioTaps>(o, network, served, clock, counters);
        page = taps->page();
        if (page != nullptr) {
          web::ScenarioView view = scenario_view(s);
          view.started = clock.now();
          page->record().set_scenario(view);
        }
        return taps;
      };
    }
    ro.log = [&](const std::string& line) {
      if (o.verbose) std::fprintf(stderr, "  %s\n", line.c_str());
      if (page == nullptr) return;
      page->record().update_scenario([&](web::ScenarioView& v) { v.log.push_back(line); });
      page->note(0, "scenario", line);
    };
    ro.decided = [&](const scenario::ExpectationResult& r) {
      if (page == nullptr) return;
      page->record().update_scenario([&](web::ScenarioView& v) {
        for (web::ExpectationView& e : v.expectations) {
          if (e.line != r.line || e.state != "open") continue;
          e.state = r.passed ? "met" : "missed";
          e.detail = r.message;
          break;
        }
      });
    };
    ro.progress = [&](Nanos t) {
      if (page != nullptr) page->record().update_scenario([&](web::ScenarioView& v) { v.elapsed = t; });
      if (tty && !o.verbose) {
        std::fprintf(stderr, "\r  %s: %.0f of %.0f s simulated", s.name.c_str(), static_cast<double>(t) / 1e9,
                     static_cast<double>(s.duration) / 1e9);
        std::fflush(stderr);
      }
    };
    if (o.verbose) std::fprintf(stderr, "%s (%s)\n", s.name.c_str(), s.file.c_str());
    scenario::ScenarioResult r;
    try {
      r = scenario::run_scenario(s, ro);
      page = nullptr;  // it ended with the run's line
    } catch (const link::LinkError& e) {
      throw CliError(kExitFailure, fmt::format("--{}: {}", o.veth ? "veth" : "iface", e.what()));
    } catch (const std::runtime_error& e) {  // a trace or capture file that cannot be written
      throw CliError(kExitFailure, e.what());
    }
    if (tty && !o.verbose) std::fprintf(stderr, "\r\033[K");
    const std::size_t passed = r.expectations.size() - (r.failed() - (r.error.empty() ? 0 : 1));
    std::printf("%s %s: %zu of %zu expectations held, %.3f s simulated in %.2f s\n", r.passed() ? "PASS" : "FAIL",
                r.name.c_str(), passed, r.expectations.size(), static_cast<double>(r.simulated) / 1e9, r.wall_seconds);
    if (r.host_stalls > 0)
      std::printf("  host stalls: %llu, longest %s (the host did not run the line's loop; docs/reliability.md)\n",
                  static_cast<unsigned long long>(r.host_stalls), runtime::stall_ms(r.longest_host_stall).c_str());
    if (!r.error.empty()) std::printf("  %s: stopped: %s\n", r.file.c_str(), r.error.c_str());
    for (const auto& e : r.expectations)
      if (!e.passed)
        std::printf("  %s:%d: %s: %s%s\n", r.file.c_str(), e.line, e.name.c_str(), e.message.c_str(), stall_before(r, e.time).c_str());
    std::fflush(stdout);
    failed += r.passed() ? 0 : 1;
    results.push_back(std::move(r));
  }
  if (!o.junit.empty()) {
    try {
      scenario::write_junit(o.junit, results);
    } catch (const std::runtime_error& e) {
      throw CliError(kExitFailure, e.what());
    }
  }
  std::printf("scenarios: %zu passed, %zu failed\n", results.size() - failed, failed);
  if (failed) throw CLI::RuntimeError(kExitFailure);
}

}  // namespace

void add_scenario_command(CLI::App& app) {
  CLI::App* scenario = app.add_subcommand("scenario", "Scripted scenarios in virtual time (docs/scenarios.md)");
  scenario->require_subcommand(1);
  auto o = std::make_shared<ScenarioOptions>();
  CLI::App* cmd = scenario->add_subcommand("run", "Run a scenario file, or every *.yaml in a directory");
  cmd->add_option("path", o->path, "Scenario file or directory")->required();
  cmd->add_option("--junit", o->junit, "Write a JUnit XML report to this file");
  cmd->add_option("--trace", o->trace, "Write the drives' trace (CSV) to this file");
  cmd->add_option("--pcap", o->pcap, "Write the master's frames (pcapng) to this file");
  cmd->add_option("--seed", o->seed, "Seed for the random faults (default: the file's seed)")
      ->each([o](const std::string&) { o->seed_given = true; });
  cmd->add_flag("--verbose,-v", o->verbose, "Print every step, fault and state change as it happens");
  cmd->add_flag("--veth", o->veth, "Real time: the built-in master and the line on a veth pair made for the run (root)");
  cmd->add_option("--iface", o->iface,
                  "Real time: serve the line on this interface for an external master; only faults and checks run");
  add_run_telemetry_options(cmd, o->telemetry);
  add_web_option(cmd, o->web);
  cmd->callback([o] { run(*o); });
}

}  // namespace vdrive::cli
