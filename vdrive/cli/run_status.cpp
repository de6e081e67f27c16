#include "vdrive/cli/run_status.hpp"

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <mutex>

#include "vdrive/control/control_protocol.hpp"
#include "vdrive/control/control_socket.hpp"

#include "vdrive/cli/line_changes.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::cli {
namespace {

constexpr Nanos kPublishPeriod = 100'000'000;  // the loop samples the ESCs 10 times a second
constexpr auto kTerminalPeriod = std::chrono::milliseconds(250);
constexpr auto kLogPeriod = std::chrono::milliseconds(1000);
constexpr auto kChangePeriod = std::chrono::milliseconds(125);  // looks for changes; the loop samples every 100 ms

Nanos steady_now() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Put in front of the logger's sinks while the line is drawn on a terminal: a log line first
// erases the status line, so the log starts at the left and the status is redrawn below it.
class EraseStatusSink final : public spdlog::sinks::base_sink<std::mutex> {
public:
  explicit EraseStatusSink(std::atomic<bool>& drawn) : drawn_(drawn) {}

protected:
  void sink_it_(const spdlog::details::log_msg&) override {
    if (drawn_.exchange(false)) std::fputs("\r\033[K", stderr);
  }
  void flush_() override {}

private:
  std::atomic<bool>& drawn_;
};

}  // namespace

runtime::WireLosses wire_losses(const fault::WireImpairment& wire) {
  runtime::WireLosses losses;
  for (const fault::Direction d : {fault::Direction::to_slaves, fault::Direction::to_master}) {
    losses.dropped += wire.counters(d).dropped;
    losses.corrupted += wire.counters(d).corrupted;
  }
  return losses;
}

void add_status_options(CLI::App* cmd, StatusMode& mode) {
  CLI::Option* on = cmd->add_flag_callback("--status", [&mode] { mode = StatusMode::on; },
                                           "Show the live status line on stderr even when it is not a terminal (one line a second)");
  CLI::Option* off = cmd->add_flag_callback("--no-status", [&mode] { mode = StatusMode::off; },
                                            "No live status line (default: shown when stderr is a terminal)");
  on->excludes(off);
}

void add_stall_option(CLI::App* cmd, double& ms) {
  cmd->add_option("--stall-threshold-ms", ms,
                  "Name a host stall when the loop runs the line's timers later than max(MS, 2 bus cycles) "
                  "(docs/reliability.md)")
      ->check(CLI::Range(0.05, 10'000.0))
      ->capture_default_str();
}

RunStatus::RunStatus(StatusMode mode, network::Network& network, const runtime::LoopCounters& counters,
                     const fault::WireImpairment* wire)
    : terminal_(::isatty(STDERR_FILENO) != 0), network_(network), counters_(counters), wire_(wire), status_(network.size()) {
  enabled_ = mode == StatusMode::on || (mode == StatusMode::automatic && terminal_);
}

RunStatus::~RunStatus() { stop(); }

void RunStatus::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  if (erase_sink_) {
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), erase_sink_), sinks.end());
    erase_sink_.reset();
  }
}

// Sampled always: what changes is logged whether the status line is shown or not.
runtime::LoopService* RunStatus::wrap(runtime::LoopService* next) {
  publisher_ = std::make_unique<runtime::LineStatusPublisher>(network_, status_, kPublishPeriod, next);
  if (wire_ != nullptr) publisher_->set_wire_source([wire = wire_] { return wire_losses(*wire); });
  publisher_->sample();  // before the loop runs: the thread may read at once
  if (enabled_ && terminal_) {
    erase_sink_ = std::make_shared<EraseStatusSink>(drawn_);
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.insert(sinks.begin(), erase_sink_);
  }
  thread_ = std::thread([this] { print_loop(); });
  return publisher_.get();
}

void RunStatus::append_later_parts(std::vector<runtime::SlaveStatus>& slaves) const {
  for (const control::RemotePart& p : later_) {
    std::vector<runtime::SlaveStatus> part(p.count);  // al_status 0: shown as "?"
    try {
      const control::ControlReply r = control::parse_reply(control::control_call(p.socket, R"({"op":"line_status"})", kPartTimeout));
      for (std::size_t i = 0; r.ok() && i < std::min(p.count, r.states.size()); ++i)
        part[i] = {r.states[i].al_status, r.states[i].al_status_code, r.states[i].rx_errors};
    } catch (const std::exception&) {  // ControlSocketError, ProtocolError: the part shows as not read
    }
    slaves.insert(slaves.end(), part.begin(), part.end());
  }
}

void RunStatus::print_loop() {
  // Changes are looked for at the publisher's pace; the line is printed at its own.
  const auto period = kChangePeriod;
  const int ticks_per_line = static_cast<int>((terminal_ ? kTerminalPeriod : kLogPeriod) / kChangePeriod);
  std::optional<runtime::StatusSample> before, last_change;
  last_change = runtime::take_sample(status_, counters_, steady_now());
  std::uint64_t stalls_seen = counters_.stalls.count();
  auto next = std::chrono::steady_clock::now();
  for (int tick = 1; !stop_.load(); ++tick) {
    next += period;
    while (!stop_.load() && std::chrono::steady_clock::now() < next) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (stop_.load()) break;
    // Stalls first: a fault they explain is logged after them.
    for (const std::string& stall : host_stall_lines(counters_.stalls, stalls_seen, slaves_before_)) spdlog::warn("{}", stall);
    runtime::StatusSample now = runtime::take_sample(status_, counters_, steady_now());
    for (const std::string& change : line_changes(*last_change, now, network_, slaves_before_)) spdlog::info("{}", change);
    last_change = now;
    if (!enabled_ || tick % ticks_per_line != 0) continue;
    runtime::StatusSample shown = now;
    append_later_parts(shown.slaves);
    const std::string line = runtime::format_status_line(shown, before ? &*before : nullptr);
    if (terminal_) {
      std::fprintf(stderr, "\r%s\033[K", line.c_str());
      drawn_.store(true);
    }
    else std::fprintf(stderr, "status: %s\n", line.c_str());
    std::fflush(stderr);
    before = std::move(now);
  }
  if (drawn_.exchange(false)) std::fprintf(stderr, "\n");
  for (const std::string& stall : host_stall_lines(counters_.stalls, stalls_seen, slaves_before_)) spdlog::warn("{}", stall);
}

}  // namespace vdrive::cli
