#pragma once
// `vdrive scenario run FILE|DIR [--junit OUT.xml] [--trace OUT.csv] [--pcap OUT.pcapng] [--seed N]
// [--verbose] [--veth | --iface IF]`: runs scenario files in virtual time (or in real time over a
// veth pair it makes, or for an external master on IF) (vdrive/scenario/, docs/scenarios.md) and
// prints a verdict per scenario and a summary. Exit 0 when every expectation held, 1 when one
// failed or a run stopped, 2 for a bad option or a scenario file with an error (file:line:column).
// With several scenarios, --trace/--pcap files get the scenario's name: OUT-<name>.csv.
namespace CLI { class App; }

namespace vdrive::cli {
void add_scenario_command(CLI::App& app);
}
