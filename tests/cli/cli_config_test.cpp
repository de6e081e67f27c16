// `vdrive --config FILE` and $VDRIVE_CONFIG (docs/cli.md "Config file"): the example file in
// docs/examples loads and its values are used, the command line wins, and a missing file, an
// unknown key or a bad value exits 2 naming the file and the key.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif
#ifndef VDRIVE_SOURCE_DIR
#error "tests/CMakeLists.txt defines VDRIVE_SOURCE_DIR (docs/examples/vdrive.toml is read from it)"
#endif

namespace vdrive::cli {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;

const std::string kExample = std::string(VDRIVE_SOURCE_DIR) + "/docs/examples/vdrive.toml";

ProcessResult vdrive(const std::vector<std::string>& args) { return test::run_process(VDRIVE_BINARY, args); }

class CliConfig : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdrive-config-test-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    ::unsetenv("VDRIVE_CONFIG");
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  std::string file(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  fs::path dir_;
};

void expect_error(const ProcessResult& r, const std::vector<std::string>& must_contain) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("vdrive: error: ", 0), 0u) << r.err;
  for (const std::string& s : must_contain) EXPECT_NE(r.err.find(s), std::string::npos) << s << " in " << r.err;
}

TEST_F(CliConfig, TheExampleFileLoadsAndItsValuesAreUsed) {
  // [od] drive = "a6b": od needs no --drive.
  ProcessResult r = vdrive({"--config", kExample, "od", "--index", "0x6040"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("6040h"), std::string::npos) << r.out;
  // [run] drive = [...]: what is missing now is only the interface.
  r = vdrive({"--config", kExample, "run"});
  expect_error(r, {"one of --iface or --tap is required"});
  // --config after the command works as well.
  EXPECT_EQ(vdrive({"od", "--index", "0x6040", "--config", kExample}).exit_code, 0);
}

TEST_F(CliConfig, TheCommandLineWins) {
  const ProcessResult r = vdrive({"--config", kExample, "od", "--drive", "nosuchdrive"});
  expect_error(r, {"unknown product 'nosuchdrive'"});
}

TEST_F(CliConfig, AMissingFileIsNamed) {
  expect_error(vdrive({"--config", (dir_ / "nosuch.toml").string(), "list-drives"}), {"--config", "nosuch.toml"});
}

TEST_F(CliConfig, AnUnknownKeyIsNamedWithItsSectionAndFile) {
  const std::string f = file("unknown.toml", "[run]\ndrive = [\"a6b\"]\nhop_dleay = 5\n");
  expect_error(vdrive({"--config", f, "list-drives"}), {f, "unknown key 'hop_dleay' in [run]"});
  const std::string top = file("top.toml", "colour = \"blue\"\n");
  expect_error(vdrive({"--config", top, "list-drives"}), {top, "unknown key 'colour' at the top level"});
  const std::string section = file("section.toml", "[scenario.run]\nsede = 3\n");
  expect_error(vdrive({"--config", section, "list-drives"}), {section, "unknown key 'sede' in [scenario.run]"});
}

// The file is TOML, read by a TOML parser: a syntax error is one, with its line and column, for
// every command alike; a section that is no command is named with the nearest one.
TEST_F(CliConfig, ATomlSyntaxErrorIsNamedWithItsLineAndColumn) {
  const std::string unclosed = file("unclosed.toml", "[run]\ndrive = [\"a6b\", \"ds5c1\"\nhop-delay = 500\n");
  const ProcessResult listed = vdrive({"--config", unclosed, "list-drives"});
  expect_error(listed, {"config file '" + unclosed + "':3:", "not TOML"});
  const ProcessResult run = vdrive({"--config", unclosed, "run", "--iface", "lo"});
  expect_error(run, {"config file '" + unclosed + "':3:", "not TOML"});
  EXPECT_EQ(run.err.find("unknown product"), std::string::npos) << "the broken array is not read as drive names: " << run.err;
}

TEST_F(CliConfig, AnUnknownSectionIsNamedWithTheNearestCommand) {
  const std::string f = file("runn.toml", "log-level = \"info\"\n[runn]\ndrive = [\"a6b\"]\n");
  expect_error(vdrive({"--config", f, "list-drives"}),
               {"config file '" + f + "':2:2: unknown section [runn], did you mean [run]? (sections are commands: "});
  const std::string nested = file("nested.toml", "[scenario.rnu]\nverbose = true\n");
  expect_error(vdrive({"--config", nested, "list-drives"}), {"unknown section [scenario.rnu], did you mean [scenario.run]?"});
}

TEST_F(CliConfig, AValueNoOptionCanTakeIsNamed) {
  const std::string f = file("tables.toml", "[run]\ndrive = [[\"a6b\"], [\"ds5c1\"]]\n");
  expect_error(vdrive({"--config", f, "list-drives"}),
               {"config file '" + f + "':2:", "'run.drive': an option takes a value or a list of values, not a list of lists"});
}

TEST_F(CliConfig, ABadValueIsNamedWithItsKeyAndFile) {
  const std::string f = file("bad.toml", "[run]\ndrive = [\"a6b\"]\nhop-delay = \"fast\"\n");
  expect_error(vdrive({"--config", f, "run", "--iface", "lo"}), {f, "key 'run.hop-delay'", "--hop-delay"});
  const std::string level = file("level.toml", "log-level = \"loud\"\n");
  expect_error(vdrive({"--config", level, "list-drives"}), {level, "key 'log-level'", "'loud' is not a log level"});
}

TEST_F(CliConfig, TheEnvironmentNamesTheDefaultFile) {
  const std::string f = file("env.toml", "[od]\ndrive = \"ds5c1\"\n");
  ::setenv("VDRIVE_CONFIG", f.c_str(), 1);
  const ProcessResult r = vdrive({"od", "--index", "0x6040", "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"product\": \"ds5c1\""), std::string::npos) << r.out;

  ::setenv("VDRIVE_CONFIG", (dir_ / "gone.toml").c_str(), 1);
  expect_error(vdrive({"list-drives"}), {"VDRIVE_CONFIG", "gone.toml"});
  // An explicit --config does not need the environment's file.
  EXPECT_EQ(vdrive({"--config", kExample, "list-drives"}).exit_code, 0);
}

}  // namespace
}  // namespace vdrive::cli
