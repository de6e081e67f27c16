#pragma once
// Runs one scenario in virtual time with the built-in master (docs/scenarios.md):
//  1. builds the line (products, plants, hop delay) on a VirtualClock and a VirtualWire;
//  2. faults due at time 0 act before the master starts (an SII error seen by the scan);
//  3. the master scans, runs the start-up SDOs in Pre-Op, maps the CiA 402 PDOs, configures the
//     process data and DC and takes the line to `master.start_state` — Safe-Op and Op through the
//     cyclic frames, as a PLC does;
//  4. then every cycle: due steps in file order, fault ends, one cyclic frame (its reply awaited
//     for half a cycle), then the drive-side checks: events, expectations, a trace row. Mailbox
//     steps (SDO writes, AL acknowledge) hold the cyclic frames while they run, as a simple master
//     would: a fraction of a millisecond normally, up to 2 x 20 ms when a reply is lost;
//  5. at `duration` every open expectation is decided.
// Same scenario and seed: the same frames, the same trace, byte for byte (virtual time).
// In real time (RunOptions::line_interface) the same steps run on the monotonic clock over real
// interfaces (realtime_wire.hpp); with an external master, steps that need the built-in master
// (state, sdo_write, acknowledge, CiA 402 steps) stop the run with an error naming the step.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "vdrive/scenario/line_tap.hpp"
#include "vdrive/scenario/scenario.hpp"
#include "vdrive/scenario/scenario_result.hpp"

namespace vdrive::scenario {

struct RunOptions {
  // Real time (empty: virtual time). The line is served on `line_interface`; the built-in master
  // sends on `master_interface` (the other end of a veth pair), or, when that is empty, an external
  // master drives the line and the scenario only injects faults and checks the drives.
  std::string line_interface;
  std::string master_interface;
  std::string trace_path;                       // CSV (trace_writer.hpp); empty: none
  std::string pcap_path;                        // pcapng of the master's port; empty: none
  std::optional<std::uint64_t> seed;            // overrides the file's seed
  std::function<void(const std::string&)> log;  // each step, fault, state and simulated second
  std::function<void(Nanos)> progress;          // every simulated second
  std::function<void(const ExpectationResult&)> decided;  // each expectation as it is decided
  LineTapFactory line_tap;                      // real time only: e.g. DDS telemetry (line_tap.hpp)
};

// Never throws for what happens in the run: a failure to start is ScenarioResult::error.
// Throws std::runtime_error only if a trace or capture file cannot be created.
ScenarioResult run_scenario(const Scenario& scenario, const RunOptions& options = {});

}  // namespace vdrive::scenario
