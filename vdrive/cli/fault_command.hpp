#pragma once
// `vdrive fault`: injects, clears and lists faults in a running `vdrive run` through its control
// socket (docs/cli.md "Runtime control"); `vdrive fault kinds` prints the catalogue. A request
// the server refuses exits 2 (its reason on stderr), a peer it denies 4, no server 1.
namespace CLI { class App; }

namespace vdrive::cli {
void add_fault_command(CLI::App& app);
}
