#include "vdrive/cli/log_level.hpp"

#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

namespace vdrive::cli {
namespace {

constexpr std::array<std::string_view, 7> kLevels = {"trace", "debug", "info", "warn", "error", "critical", "off"};
constexpr const char* kOption = "--log-level";

std::string check_level(const std::string& value) {
  if (std::find(kLevels.begin(), kLevels.end(), value) != kLevels.end()) return {};
  return fmt::format("'{}' is not a log level (trace, debug, info, warn, error, critical, off)", value);
}

void add_to(CLI::App& cmd) {
  if (cmd.get_option_no_throw(kOption) == nullptr)
    cmd.add_option(kOption, "Log level: trace, debug, info, warn, error, critical or off (default info); logs go to stderr")
        ->type_name("LEVEL")
        ->check(CLI::Validator(check_level, "", "log level"));
  for (CLI::App* sub : cmd.get_subcommands([](CLI::App* a) { return !a->get_name().empty(); })) add_to(*sub);
}

// The value of the deepest command in use that was given one (command line or config file).
std::string chosen_level(const CLI::App& app) {
  std::string level = "info";
  const CLI::App* cmd = &app;
  while (cmd != nullptr) {
    const CLI::Option* o = cmd->get_option_no_throw(kOption);
    if (o != nullptr && o->count() > 0) level = o->as<std::string>();
    const std::vector<CLI::App*> used = cmd->get_subcommands();
    cmd = used.empty() ? nullptr : used.front();
  }
  return level;
}

}  // namespace

void add_log_level_options(CLI::App& app) {
  add_to(app);
  app.parse_complete_callback([&app] {
    auto logger = spdlog::stderr_color_mt("vdrive");
    // A part of a line spread over processes (`run --processes`) names itself in every line.
    if (const char* name = std::getenv("VDRIVE_LOG_NAME"); name != nullptr && *name != '\0')
      logger->set_pattern(std::string("[%Y-%m-%d %H:%M:%S.%e] [") + name + "] [%^%l%$] %v");
    spdlog::set_default_logger(logger);
    spdlog::set_level(spdlog::level::from_str(chosen_level(app)));
  });
}

}  // namespace vdrive::cli
