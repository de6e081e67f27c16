// The `vdrive` command: subcommands, one file each; this file adds what every subcommand shares
// (--config, --log-level: config_file.hpp, log_level.hpp) and maps every way out to a one-line
// message on stderr and an exit code (see exit_codes.hpp and docs/cli.md).
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <exception>
#include <string>
#include <vector>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/config_file.hpp"
#include "vdrive/cli/demo_command.hpp"
#include "vdrive/cli/esi_command.hpp"
#include "vdrive/cli/network_command.hpp"
#include "vdrive/cli/fault_command.hpp"
#include "vdrive/cli/help_examples.hpp"
#include "vdrive/cli/list_drives_command.hpp"
#include "vdrive/cli/log_level.hpp"
#include "vdrive/cli/od_command.hpp"
#include "vdrive/cli/plot_command.hpp"
#include "vdrive/cli/run_command.hpp"
#include "vdrive/cli/scenario_command.hpp"
#include "vdrive/cli/signal_command.hpp"
#include "vdrive/cli/sii_command.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/cli/telemetry_command.hpp"

namespace {

int fail(int code, std::string what) {
  std::replace(what.begin(), what.end(), '\n', ' ');
  fmt::print(stderr, "vdrive: error: {}\n", what);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace vdrive::cli;
  CLI::App app{"vdrive: virtual EtherCAT servo drives", "vdrive"};
  app.set_version_flag("--version", "vdrive " VDRIVE_VERSION);
  app.require_subcommand(0, 1);
  // Inherited by the subcommands: an option they do not know (--config, a top-level
  // --log-level) is the top level's, wherever it stands on the line.
  app.fallthrough();
  add_run_command(app);
  add_list_drives_command(app);
  add_demo_command(app);
  add_esi_command(app);
  add_network_command(app);
  add_od_command(app);
  add_sii_command(app);
  add_scenario_command(app);
  add_fault_command(app);
  add_signal_command(app);
  add_plot_command(app);
  add_telemetry_command(app);
  // After every subcommand (add new ones above): each gets --log-level and its help footer.
  add_log_level_options(app);
  add_help_examples(app);

  const std::vector<std::string> args(argv + std::min(argc, 1), argv + argc);
  ConfigFile config;
  try {
    config.add_to(app, args);
    app.parse(argc, argv);
    // Checked here rather than with require_subcommand(1) so that an unknown option is named
    // first.
    if (app.get_subcommands().empty()) {
      return fail(kExitBadArguments,
                  "no command given (run, demo, scenario, fault, plot, telemetry, list-drives, od, sii, esi; see vdrive --help)");
    }
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::RuntimeError& e) {  // a subcommand asking for a specific exit code
    if (e.get_exit_code() != 0 && std::string(e.what()) != "Runtime error") {
      return fail(e.get_exit_code(), e.what());
    }
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // An unknown option is named first: CLI11 checks required options before leftovers.
    if (const std::vector<std::string> extra = app.remaining(true); !extra.empty() && e.get_name() == "RequiredError")
      return fail(kExitBadArguments, std::string(CLI::ExtrasError(extra).what()) + " (see vdrive --help)");
    return fail(kExitBadArguments, config.explain(e, args) + " (see vdrive --help)");
  } catch (const CliError& e) {
    return fail(e.exit_code(), e.what());
  } catch (const vdrive::profile::ProfileError& e) {
    // Products from --profile-dir are the user's files; a built-in one failing is a broken build.
    const bool users = std::any_of(args.begin(), args.end(), [](const std::string& a) { return a.rfind("--profile-dir", 0) == 0; });
    return fail(users ? kExitBadArguments : kExitFailure, e.what());
  } catch (const std::exception& e) {
    return fail(kExitFailure, e.what());
  }
  return kExitOk;
}
