#pragma once
// `vdrive run`'s live status line (docs/cli.md "Status line"): per slave AL state and error,
// frames in/out and per second, ESC receive errors, dropped frames, frames a wire fault lost. On stderr, rewritten in
// place 4 times a second when stderr is a terminal; `--status` forces it (not a terminal: one
// line a second), `--no-status` turns it off. The loop's side is a runtime::LineStatusPublisher
// (no lock, no allocation); a thread of its own formats and prints. On a terminal, a log line
// erases the status line first (a sink put in front of spdlog's), and the status is redrawn below.
// With or without the line, the thread logs what changes at info level (line_changes.hpp): AL
// states, AL errors, drive alarms by name; and host stalls (runtime/host_stalls.hpp) at warning
// level as they happen, a fault that follows one saying so. In part 1 of `run --processes` the
// line counts and shows the later parts' slaves too (set_later_parts).
#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "vdrive/control/part_router.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/runtime/line_status.hpp"

namespace CLI { class App; }
namespace spdlog::sinks { class sink; }
namespace vdrive::fault { class WireImpairment; }

namespace vdrive::cli {

enum class StatusMode { automatic, on, off };

void add_status_options(CLI::App* cmd, StatusMode& mode);
// --stall-threshold-ms MS: the floor of the host-stall threshold (runtime::HostStalls::set_floor).
void add_stall_option(CLI::App* cmd, double& ms);

// What the status line counts of a wire fault stage: both directions' dropped and corrupted frames.
runtime::WireLosses wire_losses(const fault::WireImpairment& wire);

class RunStatus {
public:
  // `wire`: the wire fault stage the line is served behind (its losses are shown), or null.
  RunStatus(StatusMode mode, network::Network& network, const runtime::LoopCounters& counters,
            const fault::WireImpairment* wire = nullptr);
  ~RunStatus();  // stops the thread and ends the line
  RunStatus(const RunStatus&) = delete;
  RunStatus& operator=(const RunStatus&) = delete;

  // The service to serve with: the status publisher in front of `next` (and the printing thread
  // started), or `next` itself when the status line is off.
  runtime::LoopService* wrap(runtime::LoopService* next);
  // Stops the thread and ends the line (also done by the destructor).
  void stop();
  // A later part of --processes: its slaves are logged by their place in the whole line.
  void set_slaves_before(std::size_t n) { slaves_before_ = n; }
  // Part 1 of --processes: the line shows the later parts' slaves too, each part's AL states
  // asked of its control socket (line_status) as the line is printed; a part that does not
  // answer within kPartTimeout shows its slaves as "?". Before wrap().
  void set_later_parts(std::vector<control::RemotePart> parts) { later_ = std::move(parts); }

private:
  static constexpr Nanos kPartTimeout = 200'000'000;
  void print_loop();
  void append_later_parts(std::vector<runtime::SlaveStatus>& slaves) const;

  bool enabled_ = false;
  bool terminal_ = false;
  network::Network& network_;
  const runtime::LoopCounters& counters_;
  const fault::WireImpairment* wire_;
  std::size_t slaves_before_ = 0;
  std::vector<control::RemotePart> later_;
  runtime::LineStatus status_;
  std::unique_ptr<runtime::LineStatusPublisher> publisher_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> drawn_{false};  // the line is on the terminal, no newline after it yet
  std::shared_ptr<spdlog::sinks::sink> erase_sink_;  // in the logger while the line is drawn on a terminal
  std::thread thread_;
};

}  // namespace vdrive::cli
