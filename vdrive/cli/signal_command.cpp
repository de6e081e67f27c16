#include "vdrive/cli/signal_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/control_client.hpp"

namespace vdrive::cli {
namespace {

void print(const ControlTarget& t, const control::ControlReply& r) {
  if (t.json) return;
  for (const control::SignalStatus& s : r.signals) {
    if (s.name == s.point) fmt::print("{}\t{}\t{}\n", s.point, s.type, s.value);
    else fmt::print("{}\t{}\t{}\t{}\n", s.name, s.point, s.type, s.value);
  }
}

// "1", "-5", "0x10", "true", "off": what a person types for a value.
std::int64_t value_of(const std::string& text) {
  if (text == "true" || text == "on") return 1;
  if (text == "false" || text == "off") return 0;
  std::size_t used = 0;
  std::int64_t v = 0;
  try {
    v = std::stoll(text, &used, 0);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw CliError(kExitBadArguments, fmt::format("signal set: '{}' is not a value (an integer, 0x hex, on/off or true/false)", text));
  return v;
}

}  // namespace

void add_signal_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("signal", "Read and set signals (I/O channels, switches, brakes) of a running vdrive run");
  cmd->require_subcommand(1);
  auto t = std::make_shared<ControlTarget>();
  auto signal = std::make_shared<std::string>();
  auto value = std::make_shared<std::string>();

  CLI::App* list = cmd->add_subcommand("list", "The network file's named signals with their values");
  add_control_target(list, *t);
  list->callback([t] {
    const control::ControlReply r = control_request(*t, {{"op", "signals"}}, "signal");
    if (!t->json && r.signals.empty()) fmt::print("the network names no signals (read any point with: vdrive signal get 'SLAVE INDEX:SUB')\n");
    print(*t, r);
  });

  CLI::App* get = cmd->add_subcommand("get", "One signal's value");
  add_control_target(get, *t);
  get->add_option("signal", *signal, "A named signal, or a point: 'SLAVE INDEX:SUB' or SLAVE.CONNECTION")->required();
  get->callback([t, signal] { print(*t, control_request(*t, {{"op", "signal_get"}, {"signal", *signal}}, "signal")); });

  CLI::App* set = cmd->add_subcommand("set", "Set a signal (until a wire or the firmware writes it again)");
  add_control_target(set, *t);
  set->add_option("signal", *signal, "A named signal, or a point: 'SLAVE INDEX:SUB' or SLAVE.CONNECTION")->required();
  set->add_option("value", *value, "An integer, 0x hex, on/off or true/false")->required();
  set->callback([t, signal, value] {
    print(*t, control_request(*t, {{"op", "signal_set"}, {"signal", *signal}, {"value", value_of(*value)}}, "signal"));
  });
}

}  // namespace vdrive::cli
