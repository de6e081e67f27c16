#include "vdrive/cli/network_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/exit_codes.hpp"
#include "vdrive/cli/output_file.hpp"
#include "vdrive/machine/eni_reader.hpp"

namespace vdrive::cli {
namespace {

struct NetworkCommandOptions {
  std::string eni;
  std::vector<std::string> esi_dirs;
  std::string output;
  std::string profile_dir;
};

void run(const NetworkCommandOptions& o) {
  machine::EniNetwork n;
  try {
    n = machine::read_eni(o.eni, o.esi_dirs, o.profile_dir);
  } catch (const machine::NetworkFileError& e) {
    throw CliError(kExitBadArguments, e.what());
  }
  // Warnings also go to stderr: the file's comments are easily not read.
  for (const std::string& w : n.warnings) fmt::print(stderr, "vdrive network: warning: {}\n", w);
  const std::string yaml = machine::to_network_yaml(n.network, n.notes);
  if (o.output.empty() || o.output == "-") {
    std::fwrite(yaml.data(), 1, yaml.size(), stdout);
    return;
  }
  write_output_file(o.output, yaml);
}

}  // namespace

void add_network_command(CLI::App& app) {
  auto o = std::make_shared<NetworkCommandOptions>();
  CLI::App* cmd = app.add_subcommand("network", "Write the network file (YAML) for a master's ENI");
  cmd->add_option("--from-eni", o->eni, "The ENI (EtherCATConfig XML) the master was configured with")->required();
  cmd->add_option("--esi-dir", o->esi_dirs, "Search DIR (recursively) for the slaves' ESI files (repeat)");
  cmd->add_option("--output,-o", o->output, "Output file (default: stdout)");
  cmd->add_option("--profile-dir", o->profile_dir, "Load products from DIR/<id>/ instead of the built-in ones");
  cmd->callback([o] { run(*o); });
}

}  // namespace vdrive::cli
