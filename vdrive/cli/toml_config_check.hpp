#pragma once
// A config file read as TOML by a TOML parser (toml++) before CLI11 takes its options: a syntax
// error, a [section] that is no command, or a value no option can take (a table inside an
// array, an array of arrays) is a CliError (exit 2) naming the file, line, column and problem,
// instead of being half read by CLI11's line-oriented reader.
#include <string>
#include <string_view>

namespace CLI { class App; }

namespace vdrive::cli {

// `text` is the file's content, `file` its name for messages; sections are checked against the
// subcommands of `app` (nested: [scenario.run]).
void check_toml_config(std::string_view text, const std::string& file, const CLI::App& app);

}  // namespace vdrive::cli
