#pragma once
// The footers of `vdrive --help` and `vdrive COMMAND --help`: examples and exit codes, kept in one
// table beside each other so they read alike. A command not in the table keeps its own footer.
namespace CLI { class App; }

namespace vdrive::cli {
// Call after every subcommand is added.
void add_help_examples(CLI::App& app);
}
