// Every command of `vdrive` found from `vdrive --help` (so one added later is covered too):
// `--help` exits 0 and names the command's options, `--log-level` among them; an unknown option
// exits 2 with one error line naming it; a bad log level exits 2 naming the value and the
// allowed ones (docs/cli.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif

namespace vdrive::cli {
namespace {

using test::ProcessResult;

ProcessResult vdrive(const std::vector<std::string>& args) { return test::run_process(VDRIVE_BINARY, args); }

// The names listed under "Subcommands:" in a help text.
std::vector<std::string> subcommands_in(const std::string& help) {
  std::vector<std::string> names;
  const std::size_t at = help.find("Subcommands:");
  if (at == std::string::npos) return names;
  std::istringstream lines(help.substr(at));
  std::string line;
  std::getline(lines, line);
  const std::regex entry(R"(^  ([a-z][a-z0-9-]*)\s)");
  while (std::getline(lines, line)) {
    std::smatch m;
    if (std::regex_search(line, m, entry)) names.push_back(m[1]);
    else if (!line.empty() && line[0] != ' ') break;
  }
  return names;
}

// Every runnable command: {"run"}, {"scenario", "run"}, {"fault", "inject"}, ...
std::vector<std::vector<std::string>> leaf_commands() {
  std::vector<std::vector<std::string>> leaves, todo{{}};
  while (!todo.empty()) {
    std::vector<std::string> path = todo.back();
    todo.pop_back();
    std::vector<std::string> args = path;
    args.push_back("--help");
    const std::vector<std::string> subs = subcommands_in(vdrive(args).out);
    if (subs.empty() && !path.empty()) leaves.push_back(path);
    for (const std::string& s : subs) {
      std::vector<std::string> next = path;
      next.push_back(s);
      todo.push_back(next);
    }
  }
  std::sort(leaves.begin(), leaves.end());
  return leaves;
}

std::string joined(const std::vector<std::string>& path) {
  std::string s;
  for (const std::string& p : path) s += (s.empty() ? "" : " ") + p;
  return s;
}

// Options each command's help must name (besides --help and --log-level).
const std::map<std::string, std::vector<std::string>> kOptions = {
    {"run", {"--iface", "--tap", "--drive", "--plant", "--hop-delay", "--profile-dir", "--rt-priority", "--control",
             "--no-control", "--fault-seed", "--no-qdisc-bypass", "--status", "--no-status"}},
    {"demo", {"--drive", "--suffix", "--cycles", "--cycle-us", "--sine-seconds", "--keep-running"}},
    {"od", {"--drive", "--index", "--json", "--profile-dir"}},
    {"sii", {"--drive", "--output", "--hex", "--profile-dir"}},
    {"esi", {"--drive", "--output", "--without-od", "--eeprom-image", "--profile-dir"}},
    {"scenario run", {"--junit", "--trace", "--pcap", "--seed", "--verbose", "--veth", "--iface"}},
    {"fault inject", {"--iface", "--control", "--json", "--slave", "--port", "--duration", "--probability", "--direction", "--delay",
                      "--count", "--abort-code", "--code", "--position", "--load-scale", "--force"}},
    {"fault clear", {"--iface", "--control", "--json", "--all"}},
    {"fault list", {"--iface", "--control", "--json"}},
    {"plot", {"--output", "--slave", "--title", "--size", "--from-zero"}},
};

TEST(CliHelp, EveryCommandIsFound) {
  const std::vector<std::vector<std::string>> leaves = leaf_commands();
  for (const auto& [name, options] : kOptions) {
    EXPECT_TRUE(std::any_of(leaves.begin(), leaves.end(), [&](const auto& p) { return joined(p) == name; }))
        << "vdrive --help does not lead to `" << name << "`";
  }
}

TEST(CliHelp, EveryCommandHasHelpNamingItsOptions) {
  for (const std::vector<std::string>& path : leaf_commands()) {
    SCOPED_TRACE(joined(path));
    std::vector<std::string> args = path;
    args.push_back("--help");
    const ProcessResult r = vdrive(args);
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_NE(r.out.find("Usage: vdrive " + joined(path)), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("--log-level"), std::string::npos) << r.out;
    const auto expected = kOptions.find(joined(path));
    if (expected == kOptions.end()) continue;
    for (const std::string& option : expected->second) EXPECT_NE(r.out.find(option), std::string::npos) << option << "\n" << r.out;
  }
}

TEST(CliHelp, TopLevelHelpNamesTheGlobalOptionsAndExitCodes) {
  const ProcessResult r = vdrive({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s : {"--config", "--log-level", "--version", "Exit codes", "plot", "scenario", "fault"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

TEST(CliHelp, AnUnknownOptionExitsTwoNamingIt) {
  for (const std::vector<std::string>& path : leaf_commands()) {
    SCOPED_TRACE(joined(path));
    std::vector<std::string> args = path;
    args.push_back("--no-such-option");
    const ProcessResult r = vdrive(args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err.rfind("vdrive: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("--no-such-option"), std::string::npos) << r.err;
  }
}

TEST(CliHelp, ABadLogLevelExitsTwoNamingValueAndChoices) {
  for (const std::vector<std::string>& path : leaf_commands()) {
    SCOPED_TRACE(joined(path));
    std::vector<std::string> args = path;
    args.insert(args.end(), {"--log-level", "loud"});
    const ProcessResult r = vdrive(args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--log-level: 'loud' is not a log level (trace, debug, info, warn, error, critical, off)"),
              std::string::npos)
        << r.err;
  }
  // Before the command as well as after it.
  const ProcessResult r = vdrive({"--log-level", "loud", "list-drives"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'loud'"), std::string::npos) << r.err;
}

TEST(CliHelp, AGoodLogLevelIsAcceptedBeforeOrAfterTheCommand) {
  EXPECT_EQ(vdrive({"--log-level", "off", "list-drives"}).exit_code, 0);
  EXPECT_EQ(vdrive({"list-drives", "--log-level", "trace"}).exit_code, 0);
}

}  // namespace
}  // namespace vdrive::cli
