#include "vdrive/cli/demo_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <map>
#include <memory>
#include <atomic>
#include <chrono>
#include <csignal>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <limits>
#include <functional>
#include <vector>

#include "master/cia402_program.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/line_changes.hpp"
#include "vdrive/cli/telemetry_command.hpp"
#include "vdrive/cli/veth_pair.hpp"
#include "vdrive/cli/web_option.hpp"
#include "vdrive/control/fault_service.hpp"
#include "vdrive/fault/impaired_link.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/telemetry/loop_services.hpp"
#include "vdrive/link/raw_socket_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/runtime/time_slice.hpp"
#include "vdrive/telemetry/telemetry_client.hpp"
#include "vdrive/telemetry/topics.hpp"

namespace vdrive::cli {

namespace {

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");
extern "C" void on_signal(int) { g_stop.store(true); }

struct DemoOptions {
  std::vector<std::string> drives{"a6b", "ds5c1", "ds1000a"};
  std::string suffix;
  bool keep_running = false;          // keep the drives moving until Ctrl-C (default on a terminal)
  bool once = false;                  // end after the run even on a terminal
  std::string web = "8080";           // the live page (docs/web.md); empty: none
  bool web_given = false;             // --web on the command line: failing to serve it is an error
  std::uint64_t op_cycles = 500;      // 0: stop at Pre-Op
  long long cycle_us = 1000;          // every product supports 1 ms
  double sine_seconds = 2.0;          // CiA 402 sine in csp after Op (0: process data only)
  bool telemetry = true;              // publish DDS telemetry and show it live (docs/telemetry.md)
  std::optional<int> domain;
};

// The demo runs as root, so its line's loop and its master take SCHED_FIFO as `vdrive run
// --rt-priority` and integration.cia402_sine do: on a busy host an ordinary thread waits for the
// other tasks' scheduler tick now and then (4 ms here), a host stall the drives see
// (docs/reliability.md). Memory is not locked (DDS maps large segments). Only the calling thread.
constexpr int kLoopPriority = 80, kMasterPriority = 70;
bool enter_fifo(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  return ::sched_setscheduler(0, SCHED_FIFO, &param) == 0;
}

// The drives' side of the demo: a Network served by the event loop in its own thread, which
// alone touches the network from start to join. The line has the runtime fault control (for the
// page's fault buttons), and optionally DDS telemetry and the web page, as `vdrive run` has.
class ServedLine {
public:
  ServedLine(const std::vector<std::string>& drives, const std::string& iface, std::optional<int> telemetry_domain,
             const std::string& web, bool web_given)
      : network_(drives, clock_), link_(iface), impaired_(link_, wire_, network_, clock_), faults_(network_, &wire_, &impaired_),
        telemetry_(telemetry_domain ? std::make_unique<telemetry::LineTelemetry>(network_, impaired_, clock_, counters_, &faults_,
                                                                                  telemetry::LineTelemetryOptions{100.0, *telemetry_domain, {}, {}}, nullptr)
                                    : nullptr),
        page_(start_web(web, network_, clock_, counters_, &faults_, "demo", iface, nullptr, !web_given)),
        services_(telemetry_ ? &telemetry_->service() : static_cast<runtime::LoopService*>(&faults_),
                  page_ ? &page_->service() : nullptr),
        thread_([this] {
          // As `vdrive run` by default: where the kernel has it, a short slice lets the line's
          // wake-ups preempt the demo's master and the host's other tasks (runtime/time_slice.hpp).
          (void)runtime::set_time_slice(100'000);
          realtime_ = enter_fifo(kLoopPriority);
          runtime::serve(network_, telemetry_ ? telemetry_->link() : impaired_, clock_, stop_, counters_, &services_);
        }) {}
  ~ServedLine() { stop(); }
  // Ends the event loop and waits for its thread; the counters are final afterwards.
  void stop() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }
  const runtime::LoopCounters& counters() const { return counters_; }
  const runtime::HostStalls& stalls() const { return counters_.stalls; }
  bool realtime() const { return realtime_.load(); }
  const web::WebServer* page() const { return page_.get(); }

private:
  MonotonicClock clock_;
  network::Network network_;
  link::RawSocketLink link_;
  fault::WireImpairment wire_{1};
  fault::ImpairedLink impaired_;
  control::FaultService faults_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> realtime_{false};
  runtime::LoopCounters counters_;
  std::unique_ptr<telemetry::LineTelemetry> telemetry_;
  std::unique_ptr<web::WebServer> page_;
  telemetry::LoopServices services_;
  std::thread thread_;  // last: starts once everything it uses exists
};

// The live view of `vdrive telemetry`, from a DDS subscriber of its own (the same path another
// process or machine would use): each axis about every 250 ms of sample time, as plain lines.
class TelemetryView {
public:
  explicit TelemetryView(int domain)
      : client_(domain), thread_([this] {
          std::map<int, Nanos> shown;
          telemetry::TelemetryHandlers h;
          h.axis = [&shown](const telemetry::AxisSample& a) {
            auto [it, fresh] = shown.try_emplace(a.slave, a.time);
            if (!fresh && a.time - it->second < 250'000'000) return;
            it->second = a.time;
            fmt::print("telemetry: {}\n", telemetry_axis_line(a));
            std::fflush(stdout);
          };
          while (!stop_.load()) client_.poll(50'000'000, h);
        }) {}
  ~TelemetryView() {
    stop_.store(true);
    thread_.join();
  }

private:
  telemetry::TelemetryClient client_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Each host stall of the served line as it happens (runtime/host_stalls.hpp), printed from a
// thread of its own: a drive that then fails has its cause on the screen.
class StallWatch {
public:
  explicit StallWatch(const runtime::HostStalls& stalls)
      : stalls_(stalls), seen_(stalls.count()), thread_([this] {
          while (!stop_.load()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            print();
          }
          print();
        }) {}
  ~StallWatch() {
    stop_.store(true);
    thread_.join();
  }

private:
  void print() {
    const std::vector<std::string> lines = host_stall_lines(stalls_, seen_);
    for (const std::string& line : lines) fmt::print("{}\n", line);
    if (!lines.empty()) std::fflush(stdout);
  }

  const runtime::HostStalls& stalls_;
  std::uint64_t seen_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// What a failure of the demo adds when the host stalled during it: the drives' trouble may be
// the host's, not vdrive's (docs/reliability.md "Host stalls").
std::string stall_note(const runtime::HostStalls& stalls) {
  const std::uint64_t n = stalls.count();
  if (n == 0) return "";
  return fmt::format(" after {} host stall{} (longest {}): the host did not run vdrive's loop for that long; see the "
                     "\"host stall\" lines above and docs/reliability.md",
                     n, n == 1 ? "" : "s", runtime::stall_ms(stalls.longest()));
}

void print_slaves(const master::Master& m) {
  for (const master::Slave& s : m.slaves()) fmt::print("  {}\n", master::describe(s));
}

void run_demo(const DemoOptions& opt) {
  // Product ids first: a typo is a bad argument, reported before touching the system.
  for (const std::string& id : opt.drives) {
    try {
      (void)profile::load_profile(id);
    } catch (const profile::ProfileError& e) {
      throw CliError(kExitBadArguments, e.what());
    }
  }
  if (::geteuid() != 0) {
    throw CliError(kExitNotPermitted, "demo needs root: it creates a veth pair and opens raw sockets");
  }
  VethPair veth("vdrive-m" + opt.suffix, "vdrive-s" + opt.suffix);
  fmt::print("veth pair: {} (master) <-> {} (drives)\n", veth.master_end(), veth.slave_end());

  try {
    std::optional<int> domain;
    if (opt.telemetry) domain.emplace(telemetry_domain(opt.domain));
    ServedLine line(opt.drives, veth.slave_end(), domain, opt.web, opt.web_given);
    StallWatch stall_watch(line.stalls());
    fmt::print("serving {} drive(s) on {}: {}\n", opt.drives.size(), veth.slave_end(), fmt::join(opt.drives, ", "));
    if (line.page() != nullptr) fmt::print("web page: {}  (open it in a browser; docs/web.md)\n", line.page()->url());
    // From a terminal the drives keep moving until Ctrl-C; in a script or CI the demo ends by itself.
    const bool moving = !opt.once && (opt.keep_running || (::isatty(STDIN_FILENO) != 0 && ::isatty(STDOUT_FILENO) != 0));
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::fflush(stdout);
    std::optional<TelemetryView> view;
    if (domain) {
      view.emplace(*domain);
      fmt::print("telemetry: DDS domain {}, 100 Hz, shown below as `vdrive telemetry` shows it\n", *domain);
    }

    link::RawSocketLink master_link(veth.master_end());
    master::Master m(master_link);
    const std::size_t n = m.scan();
    fmt::print("master on {}: {} slave(s)\n", veth.master_end(), n);
    print_slaves(m);
    if (n != opt.drives.size()) {
      throw CliError(kExitFailure, fmt::format("found {} slaves, expected {}", n, opt.drives.size()));
    }

    const bool reached = m.request_state(master::AlState::PreOp);
    fmt::print("requested Pre-Op: {}\n", reached ? "reached by every slave" : "NOT reached");
    print_slaves(m);
    if (!reached) throw CliError(kExitFailure, "not every slave reached Pre-Op");

    if (opt.op_cycles > 0) {
      // To Op with distributed clocks, then a few hundred cycles of process data.
      master::OpRunOptions op;
      op.cycle = opt.cycle_us * 1000;
      op.cycles = opt.op_cycles;
      op.dc = true;
      op.drift_frames = 2000;
      op.reply_timeout = 100'000'000;  // the demo shares the host: late replies still count, lost ones fail
      // The drives move: each is enabled in csp and follows a 0.5 Hz sine of a quarter of a motor
      // revolution. A full revolution (188 r/min peak) was too fast for virtual machines: a stall
      // of the whole host for 3 ms took the A6B out of its 0.012 rev window in about 1 run in 5
      // (docs/performance.md); at a quarter the same stall uses a fifth of the window.
      std::optional<master::SineProgram> program;
      if (opt.sine_seconds > 0) {
        master::SineProgramOptions sine;
        sine.cycle = op.cycle;
        // Until Ctrl-C: a motion as long as a year, ended by the stop flag.
        sine.motion = moving ? Nanos{365LL * 24 * 3600 * 1'000'000'000} : static_cast<Nanos>(opt.sine_seconds * 1e9);
        sine.frequency_hz = 0.5;
        sine.revolutions = 0.25;
        program.emplace(sine);
        program->attach(op);
        op.cycles = std::max(op.cycles, program->cycles_needed(op.cycle));
      }
      if (moving) {
        fmt::print("the drives keep moving until Ctrl-C\n");
        std::fflush(stdout);
        // Only Ctrl-C ends it. As a PLC would, the master takes a slave that leaves Op (a fault from
        // the page, a watchdog after a host stall) back to Op, and the sine program resets a faulted
        // drive and moves it again once its cause is gone. A lost frame is given up after 20 ms,
        // well inside the SM watchdog, so one loss does not take the line out of Op.
        op.cycles = std::numeric_limits<std::uint64_t>::max();
        op.done = [] { return g_stop.load(); };
        op.recover = true;
        op.reply_timeout = 20'000'000;
      }
      // The master's cycles on time too (threads started before this keep their policy).
      const bool master_fifo = enter_fifo(kMasterPriority);
      fmt::print("scheduling: the line's loop {}, the master {}\n", line.realtime() ? "SCHED_FIFO 80" : "normal (SCHED_FIFO refused)",
                 master_fifo ? "SCHED_FIFO 70" : "normal (SCHED_FIFO refused)");
      const master::OpRunResult r = master::run_to_op(m, op, [](const std::string& line) { fmt::print("  {}\n", line); });
      for (const std::string& note : r.notes) fmt::print("  note: {}\n", note);
      if (!r.reached_op) throw CliError(kExitFailure, r.error + stall_note(line.stalls()));
      fmt::print("Op with DC at {} us: {} cycles, working counter {} expected, {} wrong, {} lost, worst lateness {} us\n",
                 opt.cycle_us, r.stats.cycles, r.layout.expected_wkc, r.stats.wrong_wkc, r.stats.lost_frames,
                 r.stats.max_late / 1000);
      if (!r.ok())
        throw CliError(kExitFailure, fmt::format("{} wrong working counters in Op{}", r.stats.wrong_wkc, stall_note(line.stalls())));
      if (program) {
        std::size_t failed = 0;
        for (const master::DriveResult& d : program->results()) {
          fmt::print("{}\n", master::describe(d));
          if (!d.ok()) ++failed;
        }
        if (failed > 0)
          throw CliError(kExitFailure, fmt::format("{} drive(s) did not follow the sine{}", failed, stall_note(line.stalls())));
      }
    }

    if (moving && opt.op_cycles == 0) {  // no cyclic master: the line stays in Pre-Op until Ctrl-C
      fmt::print("drives keep running on {} (master end {}); Ctrl-C to stop\n", veth.slave_end(), veth.master_end());
      std::fflush(stdout);
      while (!g_stop.load()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    view.reset();
    line.stop();
    fmt::print("frames served: {} in, {} out\n", line.counters().frames_in.load(), line.counters().frames_out.load());
    const std::uint64_t stalls = line.stalls().count();
    fmt::print("host stalls: {}\n", stalls == 0 ? std::string("none")
                                                : fmt::format("{}, longest {}", stalls, runtime::stall_ms(line.stalls().longest())));
  } catch (const link::LinkError& e) {
    throw CliError(e.kind() == link::LinkError::Kind::NotPermitted ? kExitNotPermitted : kExitFailure, e.what());
  } catch (const master::MasterError& e) {
    throw CliError(kExitFailure, fmt::format("master: {}", e.what()));
  } catch (const telemetry::DdsError& e) {
    throw CliError(kExitFailure, fmt::format("telemetry: {}", e.what()));
  }
  fmt::print("removed veth pair {}/{}\n", veth.master_end(), veth.slave_end());
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto opt = std::make_shared<DemoOptions>();
  CLI::App* cmd = app.add_subcommand("demo", "Run a demo line of drives on a veth pair with the built-in master");
  cmd->add_option("--drive,-d", opt->drives, "Product id of a drive, in cable order (repeatable)")
      ->capture_default_str();
  cmd->add_option("--suffix", opt->suffix, "Suffix for the veth names vdrive-m<suffix>/vdrive-s<suffix>");
  cmd->add_option("--cycles", opt->op_cycles, "Cycles to run in Op with DC (0: stop at Pre-Op)")->capture_default_str();
  cmd->add_option("--cycle-us", opt->cycle_us, "Cycle time in microseconds")
      ->check(CLI::Range(125, 100'000))
      ->capture_default_str();
  cmd->add_option("--sine-seconds", opt->sine_seconds,
                  "Seconds of CiA 402 motion in Op: every drive enabled in csp follows a 0.5 Hz sine (0: none)")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  cmd->add_flag("!--no-telemetry", opt->telemetry, "No DDS telemetry (default: published and shown live, docs/telemetry.md)");
  cmd->add_option("--domain", opt->domain, "DDS domain id 0..232 for the telemetry (default $ROS_DOMAIN_ID, else 0)");
  CLI::Option* keep = cmd->add_flag("--keep-running", opt->keep_running,
                "Keep the drives moving (and the veth pair) until Ctrl-C; the default when run from a terminal");
  cmd->add_flag("--once", opt->once, "End after --cycles / --sine-seconds even when run from a terminal")->excludes(keep);
  CLI::Option* web = add_web_option(cmd, opt->web)->capture_default_str();
  cmd->add_flag("--no-web", [opt](std::int64_t) { opt->web.clear(); }, "Do not serve the live page")->excludes(web);
  cmd->callback([opt, web] {
    opt->web_given = web->count() > 0;
    run_demo(*opt);
  });
}

}  // namespace vdrive::cli
