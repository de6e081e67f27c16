// `vdrive scenario run` as a user meets it: verdict lines, the summary, exit codes 0 / 1 / 2,
// one-line errors naming the file, line and field, and the report files it writes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif

namespace vdrive::cli {
namespace {

namespace fs = std::filesystem;

test::ProcessResult vdrive(const std::vector<std::string>& args) { return test::run_process(VDRIVE_BINARY, args, false); }

class ScenarioCli : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdrive-scenario-cli-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

const char* kPasses = R"(name: passes
duration: 600ms
segment: {slaves: [{product: ds1000a}]}
expect:
  - {name: reaches Op, slave: 1, al_state: op, by: 500ms}
)";
const char* kFails = R"(name: fails
duration: 300ms
segment: {slaves: [{product: ds1000a}]}
expect:
  - {name: impossible, slave: 1, object: 0x6041, equals: 0x1234, at: 200ms}
)";

TEST_F(ScenarioCli, PassingScenarioExitsZeroWithItsVerdictAndReports) {
  const std::string f = write("p.yaml", kPasses);
  const auto r = vdrive({"scenario", "run", f, "--junit", (dir_ / "j.xml").string(), "--trace", (dir_ / "t.csv").string(),
                         "--pcap", (dir_ / "c.pcapng").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("PASS passes: 1 of 1 expectations held, 0.600 s simulated in ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("scenarios: 1 passed, 0 failed\n"), std::string::npos) << r.out;
  EXPECT_GT(fs::file_size(dir_ / "j.xml"), 100u);
  EXPECT_GT(fs::file_size(dir_ / "t.csv"), 1000u);
  EXPECT_GT(fs::file_size(dir_ / "c.pcapng"), 1000u);
}

TEST_F(ScenarioCli, FailedExpectationExitsOneAndPointsAtItsLine) {
  const std::string f = write("f.yaml", kFails);
  const auto r = vdrive({"scenario", "run", f});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("FAIL fails: 0 of 1 expectations held"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(f + ":5: impossible: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("expected == 4660"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("scenarios: 0 passed, 1 failed\n"), std::string::npos) << r.out;
}

TEST_F(ScenarioCli, DirectoryRunsEveryFileAndNamesPerScenarioTraces) {
  write("a.yaml", kPasses);
  write("b.yaml", kFails);
  const auto r = vdrive({"scenario", "run", dir_.string(), "--trace", (dir_ / "t.csv").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("scenarios: 1 passed, 1 failed\n"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "t-passes.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "t-fails.csv"));
}

TEST_F(ScenarioCli, BrokenFileExitsTwoWithOneLineNamingFileLineAndField) {
  const std::string f = write("x.yaml", "duration: 1s\nsegment: {slaves: [{product: a6b, colour: red}]}\n");
  const auto r = vdrive({"scenario", "run", f});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "vdrive: error: " + f + ":2:35: segment.slaves[0].colour: unknown key\n");
}

TEST_F(ScenarioCli, MissingPathAndBadOptionsExitTwo) {
  auto r = vdrive({"scenario", "run", (dir_ / "none.yaml").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("none.yaml: no such file or directory"), std::string::npos) << r.err;
  r = vdrive({"scenario", "run"});
  EXPECT_EQ(r.exit_code, 2);
  r = vdrive({"scenario", "run", write("p.yaml", kPasses), "--veth", "--iface", "eth0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--veth and --iface exclude each other"), std::string::npos) << r.err;
  r = vdrive({"scenario"});
  EXPECT_EQ(r.exit_code, 2);
}

TEST_F(ScenarioCli, UnwritableReportIsAFailureNamingTheFile) {
  const auto r = vdrive({"scenario", "run", write("p.yaml", kPasses), "--trace", "/nonexistent-dir/t.csv"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent-dir/t.csv: cannot create the trace file"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace vdrive::cli
