#pragma once
// `vdrive demo`: creates a veth pair, serves a default line of drives on one end and drives it
// with the built-in master from the other, printing what a user would want to see: the slaves,
// Pre-Op, then Op with distributed clocks at 1 ms for a few hundred cycles and a summary of the
// working counters (`--cycles 0` stops at Pre-Op).
namespace CLI { class App; }

namespace vdrive::cli {
void add_demo_command(CLI::App& app);
}
