#pragma once
// `--config FILE`: options from a TOML file, checked by a TOML parser (toml_config_check.hpp) and
// then read by CLI11. Top-level keys are the global options (`log-level`); a [section] per subcommand ([run], [demo], [scenario.run], ...)
// holds that command's long option names without the dashes, e.g. `drive = ["a6b", "ds5c1"]`.
// The command line wins over the file. Without --config: the file named by $VDRIVE_CONFIG (it
// must exist), else $XDG_CONFIG_HOME/vdrive/vdrive.toml (default ~/.config/vdrive/vdrive.toml)
// if it exists. A TOML syntax error, an unknown section or key, a bad value or a missing file is a
// bad argument (2) whose message names the file and the line or key. Example: docs/examples/vdrive.toml.
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
class Error;
}  // namespace CLI

namespace vdrive::cli {

class ConfigFile {
public:
  // Adds --config to `app` (call before parsing). Throws CliError if $VDRIVE_CONFIG names a file
  // that does not exist and the command line has no --config.
  void add_to(CLI::App& app, const std::vector<std::string>& args);
  // A parse error's message, with the file and key named when the error came from the file.
  std::string explain(const CLI::Error& error, const std::vector<std::string>& args) const;
  // The file being read (--config's value, else the default).
  std::string file() const;

private:
  CLI::App* app_ = nullptr;
  std::string default_path_;
  std::shared_ptr<std::vector<std::string>> keys_ = std::make_shared<std::vector<std::string>>();  // "section.key" as read
};

}  // namespace vdrive::cli
