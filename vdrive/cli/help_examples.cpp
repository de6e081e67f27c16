#include "vdrive/cli/help_examples.hpp"

#include <CLI/CLI.hpp>

#include <string>
#include <utility>

namespace vdrive::cli {
namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 ok, 1 failure, 2 bad arguments or input file, 3 no such interface or down, 4 not permitted,\n"
    "5 a needed program is missing (docs/cli.md).";

const std::pair<const char*, const char*> kExamples[] = {
    {"run",
     "Examples:\n"
     "  vdrive run --iface eth1 --drive a6b --drive ds5c1 --drive ds1000a\n"
     "  vdrive run --tap vdrive0 -d a6b --plant 1:scenarios/plants/a6b_brake_axis.yaml --status\n"
     "  vdrive --config site.toml run --iface eth1 --log-level debug\n"},
    {"demo",
     "Examples:\n"
     "  vdrive demo                      # a6b, ds5c1, ds1000a: scan, Pre-Op, Op with DC, a sine in csp\n"
     "  vdrive demo -d a6b --cycles 0    # stop at Pre-Op\n"},
    {"od",
     "Examples:\n"
     "  vdrive od -d a6b --index 0x6040\n"
     "  vdrive od -d ds5c1 --json > ds5c1-od.json\n"},
    {"sii",
     "Examples:\n"
     "  vdrive sii -d a6b -o a6b.bin\n"
     "  vdrive sii -d ds1000a --hex | head\n"},
    {"esi",
     "Examples:\n"
     "  vdrive esi -d a6b -o a6b.xml\n"
     "  vdrive esi -d ds5c1 --without-od\n"},
    {"run_scenario",  // `scenario run`, looked up under its parent
     "Examples:\n"
     "  vdrive scenario run scenarios/modes_csp.yaml --trace csp.csv && vdrive plot csp.csv\n"
     "  vdrive scenario run scenarios/ --junit report.xml\n"
     "Exit 0 when every expectation held, 1 when one failed, 2 for a bad option or scenario file.\n"},
    {"fault",
     "Examples:\n"
     "  vdrive fault inject --iface eth1 drop --probability 0.5 --duration 300ms\n"
     "  vdrive fault list --iface eth1\n"
     "  vdrive fault clear --iface eth1 --all\n"},
};

void set_footers(CLI::App& cmd, const std::string& parent) {
  for (CLI::App* sub : cmd.get_subcommands([](CLI::App* a) { return !a->get_name().empty(); })) {
    const std::string key = parent == "scenario" ? sub->get_name() + "_scenario" : sub->get_name();
    std::string footer;
    for (const auto& [name, text] : kExamples)
      if (key == name || (parent == "fault" && std::string(name) == "fault")) footer = text;
    if (!footer.empty()) sub->footer(footer + kExitCodes);
    else sub->footer(sub->get_footer().empty() ? std::string(kExitCodes) : sub->get_footer() + "\n" + kExitCodes);
    set_footers(*sub, sub->get_name());
  }
}

}  // namespace

void add_help_examples(CLI::App& app) {
  set_footers(app, "");
  app.footer(std::string(kExitCodes) +
             "\nEvery command takes --log-level LEVEL and --config FILE; `vdrive COMMAND --help` shows its options.");
}

}  // namespace vdrive::cli
