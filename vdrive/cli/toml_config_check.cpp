#include "vdrive/cli/toml_config_check.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <toml++/toml.h>

#include <vector>

#include "common/nearest_word.hpp"
#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/exit_codes.hpp"

namespace vdrive::cli {
namespace {

[[noreturn]] void fail(const std::string& file, const toml::source_region& at, const std::string& what) {
  throw CliError(kExitBadArguments, fmt::format("config file '{}':{}:{}: {}", file, at.begin.line, at.begin.column, what));
}

std::string names_of(const std::vector<const CLI::App*>& commands) {
  std::string s;
  for (const CLI::App* c : commands) s += (s.empty() ? "" : ", ") + c->get_name();
  return s;
}

// A value an option can take: a scalar, or an array of scalars.
void check_value(const toml::node& value, const std::string& file, const std::string& key) {
  if (const toml::array* a = value.as_array()) {
    for (const toml::node& item : *a)
      if (item.is_array() || item.is_table())
        fail(file, item.source(), fmt::format("'{}': an option takes a value or a list of values, not a list of {}", key,
                                             item.is_array() ? "lists" : "tables"));
  }
}

void check_table(const toml::table& table, const std::string& file, const CLI::App& command, const std::string& path) {
  for (const auto& [key, value] : table) {
    const std::string name(key.str());
    const std::string full = path.empty() ? name : path + "." + name;
    if (const toml::table* section = value.as_table()) {
      const CLI::App* sub = nullptr;
      std::vector<const CLI::App*> subs;
      for (const CLI::App* c : command.get_subcommands([](const CLI::App*) { return true; })) {
        subs.push_back(c);
        if (c->get_name() == name) sub = c;
      }
      if (sub == nullptr) {
        std::vector<std::string_view> candidates;
        for (const CLI::App* c : subs) candidates.push_back(c->get_name());
        const auto best = nearest_word(name, candidates);
        fail(file, key.source(), fmt::format("unknown section [{}]{} ({}: {})", full,
                                             best ? fmt::format(", did you mean [{}]?", path.empty() ? std::string(*best) : path + "." + std::string(*best)) : "",
                                             path.empty() ? "sections are commands" : "sections under [" + path + "]",
                                             names_of(subs)));
      }
      check_table(*section, file, *sub, full);
    } else {
      check_value(value, file, full);
    }
  }
}

}  // namespace

void check_toml_config(std::string_view text, const std::string& file, const CLI::App& app) {
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    fail(file, e.source(), fmt::format("not TOML: {}", e.description()));
  }
  check_table(root, file, app, "");
}

}  // namespace vdrive::cli
