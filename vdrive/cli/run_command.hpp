#pragma once
// `vdrive run`: serves a line of drives on an interface (--iface) or a TAP device (--tap) until
// SIGINT/SIGTERM, then exits 0. Errors leave as CliError with the exit codes of exit_codes.hpp.
namespace CLI { class App; }

namespace vdrive::cli {
void add_run_command(CLI::App& app);
}
