#pragma once
// `vdrive signal`: reads and sets signals of a running `vdrive run` through its control socket:
// the network file's named signals and any point ("di 0x6000:1", "x.home"; docs/networks.md
// "Signals"). Exit codes as `vdrive fault`: refused 2, denied 4, no server 1.
namespace CLI { class App; }

namespace vdrive::cli {
void add_signal_command(CLI::App& app);
}
