#include "vdrive/cli/config_file.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/toml_config_check.hpp"

namespace vdrive::cli {
namespace {

// CLI11's TOML reader behind a TOML parser's check (toml_config_check.hpp), remembering the keys
// it read so an error can be traced to the file.
class RecordingToml : public CLI::ConfigTOML {
public:
  RecordingToml(std::shared_ptr<std::vector<std::string>> keys, const ConfigFile& owner, const CLI::App& app)
      : keys_(std::move(keys)), owner_(owner), app_(app) {}
  std::vector<CLI::ConfigItem> from_config(std::istream& input) const override {
    std::stringstream text;
    text << input.rdbuf();
    check_toml_config(text.str(), owner_.file(), app_);
    std::vector<CLI::ConfigItem> items = CLI::ConfigTOML::from_config(text);
    for (const CLI::ConfigItem& item : items)
      if (item.name != "++" && item.name != "--") keys_->push_back(item.fullname());
    return items;
  }

private:
  std::shared_ptr<std::vector<std::string>> keys_;
  const ConfigFile& owner_;
  const CLI::App& app_;
};

bool given_on_command_line(const std::vector<std::string>& args, const std::string& option) {
  return std::any_of(args.begin(), args.end(), [&](const std::string& a) { return a == option || a.rfind(option + "=", 0) == 0; });
}

std::string default_config_path() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  std::string dir;
  if (xdg != nullptr && *xdg != '\0') dir = xdg;
  else if (home != nullptr && *home != '\0') dir = std::string(home) + "/.config";
  else return {};
  return dir + "/vdrive/vdrive.toml";
}

}  // namespace

void ConfigFile::add_to(CLI::App& app, const std::vector<std::string>& args) {
  app_ = &app;
  const char* env = std::getenv("VDRIVE_CONFIG");
  if (env != nullptr && *env != '\0') {
    default_path_ = env;
    std::error_code ec;
    if (!given_on_command_line(args, "--config") && !std::filesystem::is_regular_file(default_path_, ec))
      throw CliError(kExitBadArguments, fmt::format("VDRIVE_CONFIG: no such file '{}'", default_path_));
  } else {
    // Only a file that exists: the --config check below also applies to the default.
    std::error_code ec;
    default_path_ = default_config_path();
    if (!std::filesystem::is_regular_file(default_path_, ec)) default_path_.clear();
  }
  app.config_formatter(std::make_shared<RecordingToml>(keys_, *this, app));
  app.allow_config_extras(CLI::config_extras_mode::error);
  app.set_config("--config", default_path_,
                 "Read options from this TOML file (default $VDRIVE_CONFIG, else ~/.config/vdrive/vdrive.toml if it "
                 "exists): global keys at the top, a [command] section per subcommand; see docs/cli.md")
      ->type_name("FILE")
      ->check(CLI::ExistingFile.description(""));
}

std::string ConfigFile::file() const {
  // The raw value: as<>() would run the --config check again and throw from here.
  if (app_ != nullptr && app_->get_config_ptr() != nullptr && !app_->get_config_ptr()->results().empty())
    return app_->get_config_ptr()->results().front();
  return default_path_;
}

std::string ConfigFile::explain(const CLI::Error& error, const std::vector<std::string>& args) const {
  const std::string what = error.what();
  const std::string file = this->file();

  const std::string unknown = "INI was not able to parse ";
  if (what.rfind(unknown, 0) == 0) {
    const std::string full = what.substr(unknown.size());
    const std::size_t dot = full.rfind('.');
    if (dot == std::string::npos)
      return fmt::format("config file '{}': unknown key '{}' at the top level (global keys: log-level)", file, full);
    const std::string section = full.substr(0, dot);
    std::string command = section;
    std::replace(command.begin(), command.end(), '.', ' ');
    return fmt::format("config file '{}': unknown key '{}' in [{}] (keys are the long options of `vdrive {} --help`)", file,
                       full.substr(dot + 1), section, command);
  }
  if (error.get_name() == "FileError") return fmt::format("config file: {}", what);
  for (const std::string& key : *keys_) {
    const std::string name = key.substr(key.rfind('.') == std::string::npos ? 0 : key.rfind('.') + 1);
    const std::string option = "--" + name;
    const std::size_t at = what.find(option);
    const std::size_t after = at + option.size();
    const bool whole = at != std::string::npos &&
                       (after == what.size() || !(std::isalnum(static_cast<unsigned char>(what[after])) || what[after] == '-' || what[after] == '_'));
    if (whole && !given_on_command_line(args, option)) return fmt::format("config file '{}', key '{}': {}", file, key, what);
  }
  return what;
}

}  // namespace vdrive::cli
