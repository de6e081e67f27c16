#include "vdrive/cli/list_drives_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::cli {

void add_list_drives_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("list-drives", "List the drive products this build knows");
  cmd->callback([] {
    int broken = 0;
    for (const std::string& id : profile::known_products()) {
      try {
        const profile::ProductProfile p = profile::load_profile(id);
        fmt::print("{:<10} {}\n", id, p.title);
      } catch (const profile::ProfileError& e) {
        // Keep listing; a broken profile is a build defect, reported and reflected in the exit.
        fmt::print(stderr, "vdrive: error: {}\n", e.what());
        ++broken;
      }
    }
    if (broken != 0) throw CliError(kExitFailure, fmt::format("{} profile(s) failed to load", broken));
  });
}

}  // namespace vdrive::cli
