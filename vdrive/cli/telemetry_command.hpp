#pragma once
// `vdrive telemetry`: subscribes to the DDS telemetry of every vdrive in a domain and prints a
// live view or records CSV; `vdrive telemetry inject|clear|plant-set` publish a request on the
// control topic and wait for its reply (docs/telemetry.md). Also the `--telemetry` options of
// `vdrive run` and what they start.
#include <memory>
#include <optional>
#include <string>

#include "vdrive/telemetry/line_telemetry.hpp"
#include "vdrive/telemetry/samples.hpp"

namespace CLI { class App; }

namespace vdrive::cli {

void add_telemetry_command(CLI::App& app);

struct RunTelemetryOptions {
  bool enabled = false;
  double rate_hz = 100.0;
  std::optional<int> domain;
  // Not options: what `run --processes` sets for each part (telemetry::LineTelemetryOptions).
  telemetry::LinePlace place;
  telemetry::PublisherOptions requests;
};

// One axis sample as the live view shows it ("t=1.230s slave 1 Op sw=0x1237 ... pos=... ...").
std::string telemetry_axis_line(const telemetry::AxisSample& a);

// The DDS domain: `option`, else $ROS_DOMAIN_ID, else 0; CliError (exit 2) for a bad one.
int telemetry_domain(std::optional<int> option);

// --telemetry, --telemetry-rate HZ, --domain N on `vdrive run`.
void add_run_telemetry_options(CLI::App* run, RunTelemetryOptions& options);

// The line's telemetry if enabled (else nullptr), logged; CliError for a bad domain (exit 2) or
// DDS that cannot start (exit 1).
std::unique_ptr<telemetry::LineTelemetry> start_run_telemetry(const RunTelemetryOptions& options, network::Network& network,
                                                              link::Link& served, const Clock& clock,
                                                              const runtime::LoopCounters& counters,
                                                              control::FaultService* faults, std::function<void()> wake);

}  // namespace vdrive::cli
