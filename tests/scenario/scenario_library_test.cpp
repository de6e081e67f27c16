// Every file under scenarios/ passes in virtual time (one ctest case each), and a run is
// deterministic: the same scenario and seed give byte-identical traces and captures, another seed
// another run. Real time over veth: tests/integration/scenario_realtime.sh.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "vdrive/scenario/junit_writer.hpp"
#include "vdrive/scenario/scenario_loader.hpp"
#include "vdrive/scenario/scenario_runner.hpp"

namespace vdrive::scenario {
namespace {

namespace fs = std::filesystem;
const std::string kLibrary = std::string(VDRIVE_SOURCE_DIR) + "/scenarios";

std::vector<std::string> library() { return scenario_files(kLibrary); }

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class ScenarioLibrary : public ::testing::TestWithParam<std::string> {};

TEST_P(ScenarioLibrary, PassesInVirtualTime) {
  const Scenario s = load_scenario_file(GetParam());
  const ScenarioResult r = run_scenario(s);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_FALSE(r.expectations.empty()) << "a scenario checks something";
  for (const ExpectationResult& e : r.expectations) EXPECT_TRUE(e.passed) << s.file << ":" << e.line << ": " << e.name << ": " << e.message;
  EXPECT_GE(r.simulated, s.expect_stop.empty() ? s.duration : 0);
}

INSTANTIATE_TEST_SUITE_P(Files, ScenarioLibrary, ::testing::ValuesIn(library()), [](const auto& info) {
  std::string name = fs::path(info.param).stem().string();
  for (char& c : name) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

class ScenarioRuns : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdrive-runs-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  ScenarioResult run(const std::string& file, const std::string& tag, std::optional<std::uint64_t> seed = {}) {
    RunOptions o;
    o.trace_path = (dir_ / (tag + ".csv")).string();
    o.pcap_path = (dir_ / (tag + ".pcapng")).string();
    o.seed = seed;
    return run_scenario(load_scenario_file(kLibrary + "/" + file), o);
  }
  fs::path dir_;
};

TEST_F(ScenarioRuns, SameScenarioAndSeedGiveByteIdenticalTraceAndCapture) {
  // Random frame loss, DC, three drives moving: everything that could differ between runs.
  run("wire_frame_loss.yaml", "a");
  run("wire_frame_loss.yaml", "b");
  run("wire_frame_loss.yaml", "c", 99);
  const std::string a = read(dir_ / "a.csv"), b = read(dir_ / "b.csv"), c = read(dir_ / "c.csv");
  ASSERT_GT(a.size(), 100'000u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(read(dir_ / "a.pcapng"), read(dir_ / "b.pcapng"));
  EXPECT_NE(a, c) << "another seed loses other frames";
}

TEST_F(ScenarioRuns, TraceHasOneRowPerSlaveAndCycleWithTheDrivesValues) {
  const ScenarioResult r = run("startup_a6b.yaml", "t");
  std::ifstream in(dir_ / "t.csv");
  std::string header, row, last;
  std::getline(in, header);
  EXPECT_EQ(header, "time_ns,slave,al_state,al_status_code,statusword,controlword,mode,position,velocity,torque,following_error,error_code,station");
  std::size_t rows = 0;
  while (std::getline(in, row)) ++rows, last = row;
  EXPECT_GE(rows, r.cycles);
  EXPECT_NE(last.find(",1,8,0x0000,0x"), std::string::npos) << "the last row: slave 1 in Op: " << last;
  EXPECT_NE(last.find(",8,"), std::string::npos) << "mode display csp: " << last;
}

TEST_F(ScenarioRuns, CaptureIsPcapngWithEveryFrameOfTheMaster) {
  const ScenarioResult r = run("startup_a6b.yaml", "p");
  const std::string cap = read(dir_ / "p.pcapng");
  ASSERT_GT(cap.size(), 64u);
  EXPECT_EQ(cap.substr(0, 4), std::string("\x0A\x0D\x0D\x0A", 4)) << "section header block";
  EXPECT_EQ(cap.substr(8, 4), std::string("\x4D\x3C\x2B\x1A", 4)) << "byte-order magic";
  std::size_t offset = 0, packets = 0;
  while (offset + 12 <= cap.size()) {
    std::uint32_t type = 0, length = 0;
    std::memcpy(&type, cap.data() + offset, 4);
    std::memcpy(&length, cap.data() + offset + 4, 4);
    ASSERT_EQ(length % 4, 0u);
    ASSERT_LE(offset + length, cap.size());
    packets += type == 6;
    offset += length;
  }
  EXPECT_EQ(offset, cap.size());
  EXPECT_GE(packets, 2 * r.cycles) << "each cycle's frame out and back";
}

TEST_F(ScenarioRuns, JunitReportHasASuiteAScenarioAndAFailureAnExpectation) {
  ScenarioResult ok = run("startup_a6b.yaml", "j1");
  ScenarioResult bad = ok;
  bad.name = "bad";
  bad.expectations[0].passed = false;
  bad.expectations[0].message = "0x0002 at 5 ms, expected == 8";
  write_junit((dir_ / "j.xml").string(), {ok, bad});
  const std::string xml = read(dir_ / "j.xml");
  EXPECT_NE(xml.find("<testsuites tests=\"10\" failures=\"1\">"), std::string::npos) << xml.substr(0, 200);
  EXPECT_NE(xml.find("<testsuite name=\"startup_a6b\""), std::string::npos);
  EXPECT_NE(xml.find("<failure message=\"line 16: 0x0002 at 5 ms, expected == 8\""), std::string::npos);
}

TEST(ScenarioRunErrors, AFaultTheTargetCannotHaveStopsTheRunWithItsReason) {
  const Scenario s = parse_scenario(R"(duration: 1s
segment: {slaves: [{product: ds1000a}]}
timeline:
  - {at: {on: op, delay: 10ms}, fault: {kind: alarm, slave: 1, code: "24.0"}}
expect:
  - {slave: 1, al_state: op, by: 1s}
)", "x.yaml");
  const ScenarioResult r = run_scenario(s);
  EXPECT_NE(r.error.find("ds1000a has no alarm \"24.0\""), std::string::npos) << r.error;
  EXPECT_FALSE(r.passed());
  EXPECT_TRUE(r.expectations[0].passed) << "what was checked before the stop still counts";
}

TEST(ScenarioSteps, SdoReadWithAConditionIsReportedAsAnExpectation) {
  const Scenario s = parse_scenario(R"(duration: 300ms
segment: {slaves: [{product: a6b}]}
timeline:
  - {name: vendor, at: {on: op}, sdo_read: {slave: 1, index: 0x1018, subindex: 1, equals: 0x066F}}
  - {at: {on: op}, sdo_read: {slave: 1, index: 0x1018, subindex: 1, equals: 5}}
)", "r.yaml");
  const ScenarioResult r = run_scenario(s);
  ASSERT_EQ(r.expectations.size(), 2u);
  EXPECT_EQ(r.expectations[0].name, "vendor");
  EXPECT_TRUE(r.expectations[0].passed) << r.expectations[0].message;
  EXPECT_FALSE(r.expectations[1].passed);
  EXPECT_EQ(r.expectations[1].message, "read 1647, expected == 5");
  EXPECT_EQ(r.expectations[1].line, 5);
}

TEST(ScenarioRunErrors, AnObjectTheProductDoesNotHaveIsNamed) {
  const Scenario s = parse_scenario("duration: 1s\nsegment: {slaves: [{product: ds1000a}]}\nexpect:\n  - {slave: 1, object: 0x3742, equals: 1, at: 1s}\n", "x.yaml");
  const ScenarioResult r = run_scenario(s);
  EXPECT_EQ(r.error, "x.yaml:4: expect[0] (line 4): slave 1 (ds1000a) has no object 3742h:00");
}

}  // namespace
}  // namespace vdrive::scenario
