#pragma once
// WebServer: the live web page of a served line and its JSON API (docs/web.md), for `vdrive run`,
// `vdrive demo` and real-time `vdrive scenario run` with --web.
//
// Off the loop thread, as DDS telemetry is: a Sampler on the loop thread copies each axis's values
// and the line's events into a lock-free queue at 50 Hz; a pump thread moves them into a
// LineRecord and asks the loop (LoopCalls, between frames) for the ESC registers every 100 ms and
// the active faults every 250 ms; cpp-httplib's threads answer the page and the API from the
// record, and carry object reads and writes, faults, plant changes and signals to the loop
// through LoopCalls. Nothing here locks or allocates on the frame path.
//
// Bound to 127.0.0.1 unless told otherwise. Bound to any other address, every request that
// changes something needs the token made at start (Authorization: Bearer TOKEN; url() carries it
// in the fragment for the page). Changes need Content-Type: application/json (a form on another
// site cannot send one), a loopback server answers only Host names of this machine (no DNS
// rebinding), bodies are limited to 64 KiB and the live streams to 6 at a time.
//
// Part 1 of a line over processes shows the whole line: a second pump reads the later parts'
// own pages and the run's active faults (through its router, `route`) every 100 ms, so a part
// that hangs delays neither the samples nor the page; a request for one of the later parts'
// slaves goes on to the part that serves it (PartPages); faults and signals go through the router.
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/control/control_request.hpp"
#include "vdrive/runtime/loop_service.hpp"
#include "vdrive/web/part_pages.hpp"
#include "vdrive/web/web_address.hpp"

namespace vdrive::network { class Network; }
namespace vdrive::runtime { struct LoopCounters; }
namespace vdrive::control { class FaultService; }

namespace vdrive::web {

class LineRecord;

// The server could not start (the address is taken, not local, or not permitted).
class WebError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct WebServerOptions {
  WebAddress address;
  std::string source = "run";  // what serves the line: run, demo, scenario
  std::string interface;       // the served interface, for the page's title
  std::string version;
  double sample_rate_hz = 50.0;
  // The record's time origin on `clock` (time_ns 0); default: when the server starts. The parts
  // of a line over processes share one clock epoch and give 0, so their times compare.
  std::optional<Nanos> origin;
  // When set, a change needs this token even on loopback: a later part's page, which part 1's
  // page alone calls.
  std::string token;
  // A part of a line over processes (0-based, of run_parts): its fault events carry run-wide ids
  // (control/run_fault_id.hpp), as `vdrive fault list` shows them.
  std::size_t run_part = 0, run_parts = 1;
  // A line over processes: the later parts' own pages, read into this page (part_pages.hpp).
  std::vector<PartPage> parts;
  std::string parts_token;
  // Set: fault and signal requests go there (the run's PartRouter, which blocks; called on the
  // server's threads) instead of to this process's fault service alone.
  std::function<control::ControlReply(const control::ControlRequest&, std::string_view line)> route;
};

// A fresh random token (128 bits, hex), as a server beyond loopback makes for itself.
std::string new_token();

class WebServer {
public:
  // On the thread that serves the line, before the loop starts (reads the network). `faults` (may
  // be null: then fault requests are refused) carries out fault requests on the loop thread and
  // must be polled there too. `wake` (optional) cuts the loop's wait short (runtime::LoopWaker).
  // Throws WebError naming the address.
  WebServer(network::Network& network, const Clock& clock, const runtime::LoopCounters& counters,
            control::FaultService* faults, WebServerOptions options, std::function<void()> wake = {});
  ~WebServer();  // stops the server and its threads
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // Poll on the loop thread (the sampler and the calls from the server's threads).
  runtime::LoopService& service();
  // The page's address; with the token in its fragment when one is needed.
  std::string url() const;
  const std::string& token() const;
  int port() const;  // the bound port (useful with port 0 in tests)
  // A real-time scenario reports its progress here.
  LineRecord& record();
  // An event of the page's log from outside the line (a scenario's step), stamped now.
  void note(int slave, const std::string& kind, const std::string& text);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdrive::web
