#include "vdrive/cli/fault_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/control_client.hpp"
#include "vdrive/cli/fault_inject_options.hpp"
#include "vdrive/fault/fault_spec.hpp"

namespace vdrive::cli {
namespace {

using Target = ControlTarget;

control::ControlReply request(const Target& t, const nlohmann::json& req) { return control_request(t, req, "fault"); }

std::string duration_text(Nanos ns) {
  if (ns % 1'000'000'000 == 0) return fmt::format("{}s", ns / 1'000'000'000);
  if (ns >= 1'000'000) return fmt::format("{}ms", ns / 1'000'000);
  return fmt::format("{}us", ns / 1000);
}

void inject(const Target& t, const FaultInjectOptions& o) {
  const control::ControlReply r = request(t, {{"op", "inject"}, {"fault", fault_json(o)}});
  if (t.json) return;
  if (r.id != 0) fmt::print("fault {} injected\n", r.id);
  else fmt::print("one-shot fault injected\n");
}

void list(const Target& t) {
  const control::ControlReply r = request(t, {{"op", "list"}});
  if (t.json) return;
  if (r.faults.empty()) fmt::print("no active faults\n");
  for (const control::FaultStatus& f : r.faults) {
    fmt::print("{}\t{}\tfor {}\t{}\n", f.id, f.description, duration_text(f.elapsed),
               f.remaining < 0 ? "until cleared" : duration_text(f.remaining) + " left");
  }
}

void clear(const Target& t, int id, bool all) {
  if (all == (id != 0)) throw CliError(kExitBadArguments, "fault clear: give a fault ID or --all (not both)");
  if (all) {
    const control::ControlReply r = request(t, {{"op", "clear_all"}});
    if (!t.json) fmt::print("{} fault(s) cleared\n", r.cleared);
  } else {
    request(t, {{"op", "clear"}, {"id", id}});
    if (!t.json) fmt::print("fault {} cleared\n", id);
  }
}

void kinds() {
  for (const fault::FaultKindInfo& i : fault::fault_catalogue())
    fmt::print("{:<16} {:<8} {}{}\n", i.name, fault::name(i.layer), i.summary, i.one_shot ? " (one-shot)" : "");
}

}  // namespace

void add_fault_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("fault", "Inject, clear and list faults in a running vdrive run");
  cmd->require_subcommand(1);

  auto t = std::make_shared<Target>();
  auto o = std::make_shared<FaultInjectOptions>();
  CLI::App* inj = cmd->add_subcommand("inject", "Start a fault now (vdrive fault kinds lists them)");
  add_control_target(inj, *t);
  add_fault_inject_options(inj, *o);
  inj->callback([t, o] { inject(*t, *o); });

  auto id = std::make_shared<int>(0);
  auto all = std::make_shared<bool>(false);
  CLI::App* clr = cmd->add_subcommand("clear", "End a fault by its id, or all of them");
  add_control_target(clr, *t);
  clr->add_option("id", *id, "Fault id (from inject or list)")->check(CLI::PositiveNumber);
  clr->add_flag("--all", *all, "End every active fault");
  clr->callback([t, id, all] { clear(*t, *id, *all); });

  CLI::App* lst = cmd->add_subcommand("list", "Active faults: id, description, time active and left");
  add_control_target(lst, *t);
  lst->callback([t] { list(*t); });

  cmd->add_subcommand("kinds", "The fault catalogue: kind, layer, what it does")->callback(kinds);
}

}  // namespace vdrive::cli
