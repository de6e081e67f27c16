// libFuzzer target: the files a user writes, as text. Each reader must end in a value or its own
// error whose message is non-empty and names the file it read (docs: "<file>:<line>: <field>:
// <what>"), never a crash, a hang or another exception type (the target traps on those).
//
// Input: byte 0 picks the surface (byte 0 % 7), the rest is the file's text:
//   0 scenario YAML (scenario::parse_scenario; named <source>/scenarios/fuzz_input.yaml, so the
//     plant files the library's scenarios name are found);
//   1 plant YAML (plant::parse_plant_yaml, motors looked up in the built-in products);
//   2 profile.yaml, 3 alarms.yaml, 4 motors.yaml of a product (profile::parse_profile_text; the
//     other two files are the built-in product's; (byte 0 / 7) % 3 picks a6b, ds5c1, ds1000a);
//   5 a network file (machine::parse_network_file, relative to tests/products/networks);
//   6 the TOML config of `vdrive --config` (cli::check_toml_config and CLI11's reader behind
//     cli::ConfigFile, on a command tree with the real command names and a few of their options;
//     the text goes through a temporary file, as CLI11 reads only files).
#include <stdlib.h>

#include <CLI/CLI.hpp>

#include <array>
#include <cstdio>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plant/plant_yaml.hpp"
#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/config_file.hpp"
#include "vdrive/drive/product_plant.hpp"
#include "vdrive/machine/network_file.hpp"
#include "vdrive/profile/embedded_profiles.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/profile_text.hpp"
#include "vdrive/scenario/scenario_loader.hpp"

namespace {

const std::string kSource = VDRIVE_FUZZ_SOURCE_DIR;
const std::array<std::string, 3> kProducts = {"a6b", "ds5c1", "ds1000a"};

// An error must say what went wrong and in which file.
void expect_message(const std::string& what, std::string_view file) {
  if (!what.empty() && what.find(file) != std::string::npos) return;
  std::fprintf(stderr, "fuzz_config: an error that does not name %.*s: \"%s\"\n", static_cast<int>(file.size()), file.data(),
               what.c_str());
  __builtin_trap();
}

// ... and, for the YAML readers, at which line: "<file>:<line>".
void expect_file_line(const std::string& what, std::string_view file) {
  expect_message(what, file);
  for (std::size_t at = what.find(file); at != std::string::npos; at = what.find(file, at + 1)) {
    const std::size_t colon = at + file.size();
    if (colon + 1 < what.size() && what[colon] == ':' && what[colon + 1] >= '1' && what[colon + 1] <= '9') return;
  }
  std::fprintf(stderr, "fuzz_config: an error without the line in %.*s: \"%s\"\n", static_cast<int>(file.size()), file.data(),
               what.c_str());
  __builtin_trap();
}

const vdrive::profile::ProductProfile& product(std::size_t i) {
  static const std::array<vdrive::profile::ProductProfile, 3> products = {
      vdrive::profile::load_profile(kProducts[0]), vdrive::profile::load_profile(kProducts[1]),
      vdrive::profile::load_profile(kProducts[2])};
  return products[i % 3];
}

std::optional<vdrive::plant::MotorCatalogue> catalogue(std::string_view id) {
  for (std::size_t i = 0; i < kProducts.size(); ++i)
    if (kProducts[i] == id) return vdrive::drive::motor_catalogue(product(i));
  return std::nullopt;
}

const vdrive::profile::EmbeddedProfile& embedded(std::string_view id) {
  for (const auto& e : vdrive::profile::embedded_profiles())
    if (e.id == id) return e;
  __builtin_trap();
}

void profile_files(std::size_t which, std::size_t product_index, const std::string& text) {
  const std::string& id = kProducts[product_index % 3];
  const auto& e = embedded(id);
  const std::string dir = "fuzz/" + id;
  const std::string profile = which == 0 ? text : std::string(e.yaml);
  const std::string_view alarms = which == 1 ? std::string_view(text) : e.alarms_yaml;
  const std::string_view motors = which == 2 ? std::string_view(text) : e.motors_yaml;
  try {
    (void)vdrive::profile::parse_profile_text(id, profile, alarms, motors, dir);
  } catch (const vdrive::profile::ProfileError& err) {
    expect_message(err.what(), dir);
  }
}

// The real command names (sections are commands) with a few of their options of each kind.
void add_commands(CLI::App& app) {
  static std::string s;
  static std::vector<std::string> list;
  static int n = 0;
  static double x = 0;
  static bool flag = false;
  app.fallthrough();
  app.add_option("--log-level", s);
  CLI::App* run = app.add_subcommand("run");
  run->add_option("--drive", list);
  run->add_option("--hop-delay", n);
  run->add_option("--fault-seed", n);
  CLI::App* demo = app.add_subcommand("demo");
  demo->add_option("--cycles", n);
  demo->add_option("--sine-seconds", x);
  app.add_subcommand("od")->add_option("--drive", s);
  app.add_subcommand("scenario")->add_subcommand("run")->add_flag("--verbose", flag);
  app.add_subcommand("plot")->add_option("--size", s);
  for (const char* name : {"list-drives", "sii", "esi", "network"}) app.add_subcommand(name);
  CLI::App* fault = app.add_subcommand("fault");
  for (const char* name : {"inject", "clear", "list", "kinds"}) fault->add_subcommand(name);
  CLI::App* signal = app.add_subcommand("signal");
  for (const char* name : {"list", "get", "set"}) signal->add_subcommand(name);
  CLI::App* telemetry = app.add_subcommand("telemetry");
  for (const char* name : {"inject", "clear", "plant-set"}) telemetry->add_subcommand(name);
}

void toml_config(const std::string& text) {
  static const std::string file = [] {
    std::string d = (std::filesystem::temp_directory_path() / "vdrive-fuzz-config-XXXXXX").string();
    return std::string(::mkdtemp(d.data())) + "/fuzz_input.toml";
  }();
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
  }
  CLI::App app{"fuzz", "vdrive"};
  add_commands(app);
  const std::vector<std::string> args = {"--config", file};
  vdrive::cli::ConfigFile config;
  try {
    config.add_to(app, args);
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them back to front
    app.parse(reversed);
  } catch (const vdrive::cli::CliError& e) {
    expect_message(e.what(), file);
  } catch (const CLI::ParseError& e) {
    if (config.explain(e, args).empty()) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  switch (data[0] % 7) {
    case 0: {
      const std::string file = kSource + "/scenarios/fuzz_input.yaml";
      try {
        (void)vdrive::scenario::parse_scenario(text, file);
      } catch (const vdrive::scenario::ScenarioError& e) {
        expect_file_line(e.what(), file);
      }
      break;
    }
    case 1:
      try {
        (void)vdrive::plant::parse_plant_yaml(text, "fuzz_plant.yaml", catalogue);
      } catch (const vdrive::plant::PlantYamlError& e) {
        expect_file_line(e.what(), "fuzz_plant.yaml");
      }
      break;
    case 2:
    case 3:
    case 4: profile_files(data[0] % 7 - 2, data[0] / 7, text); break;
    case 5: {
      const std::string base = kSource + "/tests/products/networks";
      try {
        (void)vdrive::machine::parse_network_file(text, "fuzz_network.yaml", base);
      } catch (const vdrive::machine::NetworkFileError& e) {
        expect_file_line(e.what(), "fuzz_network.yaml");
      }
      break;
    }
    default: toml_config(text); break;
  }
  return 0;
}
