#pragma once
// `--log-level trace|debug|info|warn|error|critical|off` on the top-level command and on every
// subcommand (also as the `log-level` key of a config file section), so a subcommand needs
// nothing of its own. Before any subcommand runs, spdlog's default logger is set to write to
// stderr (stdout stays for what scripts parse) at the level given by the most specific command
// in use: `vdrive scenario run --log-level debug` beats a top-level `log-level = "warn"`.
// Default: info. A bad value is a bad argument (2) naming the value and the allowed ones.
namespace CLI { class App; }

namespace vdrive::cli {
// Call after every subcommand is added.
void add_log_level_options(CLI::App& app);
}
