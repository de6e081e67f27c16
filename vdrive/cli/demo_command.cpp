#include "vdrive/cli/demo_command.hpp"

#include <CLI/CLI.hpp>

namespace vdrive::cli {
void add_demo_command(CLI::App& app) {
  app.add_subcommand("demo", "Run a demo line of drives on a veth pair with the built-in master");
}
}  // namespace vdrive::cli
