// Scenarios on a network file: `signal` steps set signals, `signal:` expectations read them, what a
// signal names must exist (line and reason otherwise), and the file's armed faults happen.
#include <gtest/gtest.h>

#include <string>

#include "vdrive/scenario/scenario_loader.hpp"
#include "vdrive/scenario/scenario_runner.hpp"

namespace vdrive::scenario {
namespace {

// Parsed as if it were a file beside the network file, so `network:` is found.
const std::string kFile = std::string(VDRIVE_SOURCE_DIR) + "/tests/products/networks/signals.yaml";

const char* kScenario = R"(duration: 800ms
segment:
  network: signal_bench.yaml
master: {cycle: 1ms, dc: false}
timeline:
  - {at: 200ms, signal: {name: door, value: on}}
  - {at: 300ms, signal: {name: x_home, value: 1}}
  - {at: 600ms, signal: {name: 'x.home', value: 0}}
expect:
  - {name: door closed before, signal: door, equals: 0, at: 150ms}
  - {name: door open, signal: door, equals: 1, at: 250ms}
  - {name: home on the input terminal, signal: 'di 0x6000:1', equals: 1, by: 400ms, from: 300ms}
  - {name: home at the drive, slave: 4, object: 0x60FD, mask: 0x4, equals: 0x4, by: 400ms, from: 300ms}
  - {name: home released, signal: 'di 0x6000:1', equals: 0, by: 700ms, from: 600ms}
)";

TEST(ScenarioSignals, StepsSetSignalsAndExpectationsReadThem) {
  const Scenario s = parse_scenario(kScenario, kFile);
  ASSERT_EQ(s.slaves.size(), 4u);
  EXPECT_EQ(s.network.slave_names[3], "x");
  ASSERT_EQ(s.network.wires.size(), 1u);
  const ScenarioResult r = run_scenario(s);
  EXPECT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.expectations.size(), 5u);
  for (const ExpectationResult& e : r.expectations) EXPECT_TRUE(e.passed) << e.name << ": " << e.message;
}

std::string load_error(const std::string& text) {
  try {
    (void)parse_scenario(text, kFile);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ScenarioSignals, ASignalThatIsNeitherNamedNorAPointIsRefusedWithItsLine) {
  const std::string text = R"(duration: 1s
segment: {network: signal_bench.yaml}
timeline:
  - {at: 1ms, signal: {name: dor, value: 1}}
)";
  EXPECT_EQ(load_error(text), kFile + ":4:30: timeline[0].signal.name: no signal 'dor' (signals: door, x_home) and not "
                                      "a point: 'dor': expected SLAVE INDEX:SUBINDEX (e.g. 'do 0x7000:1') or "
                                      "SLAVE.CONNECTION (e.g. 'x.home')");
}

TEST(ScenarioSignals, ANetworkAndSlavesTogetherAreRefused) {
  const std::string text = R"(duration: 1s
segment:
  network: signal_bench.yaml
  slaves: [{product: a6b}]
)";
  EXPECT_NE(load_error(text).find("segment.network: a segment is a network file or a list of slaves, not both"),
            std::string::npos)
      << load_error(text);
}

TEST(ScenarioSignals, AnEntryTheSlaveLacksStopsTheRunNamingTheLine) {
  const std::string text = R"(duration: 100ms
segment: {network: signal_bench.yaml}
timeline:
  - {at: 1ms, signal: {name: 'do 0x6000:1', value: 1}}
)";
  const ScenarioResult r = run_scenario(parse_scenario(text, kFile));
  EXPECT_NE(r.error.find(":4: signal \"do 0x6000:1\": 'do' (slave 3, "), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("has no object 6000h:01h"), std::string::npos) << r.error;
}

TEST(ScenarioSignals, AValueThePointCannotHoldStopsTheRunBeforeItStarts) {
  const std::string text = R"(duration: 100ms
segment: {network: signal_bench.yaml}
timeline:
  - {at: 1ms, signal: {name: x_home, value: 5}}
)";
  const ScenarioResult r = run_scenario(parse_scenario(text, kFile));
  EXPECT_NE(r.error.find(":4: signal \"x_home\": 5 is outside 0..1"), std::string::npos) << r.error;
}

// The network file's armed faults are steps of the run at their times.
TEST(ScenarioNetworkFaults, ANetworkFilesArmedFaultHappensAtItsTime) {
  const std::string text = R"(duration: 1s
segment: {network: armed_fault.yaml}
expect:
  - {name: no alarm yet, slave: 1, object: 0x603F, equals: 0, at: 250ms}
  - {name: encoder alarm, slave: 1, object: 0x603F, min: 1, by: 600ms}
)";
  const Scenario s = parse_scenario(text, kFile);
  ASSERT_EQ(s.steps.size(), 1u);
  EXPECT_EQ(s.steps[0].when.delay, 300'000'000);
  ASSERT_TRUE(std::holds_alternative<FaultAction>(s.steps[0].action));
  EXPECT_EQ(std::get<FaultAction>(s.steps[0].action).fault.kind, fault::FaultKind::encoder_error);
  const ScenarioResult r = run_scenario(s);
  EXPECT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.expectations.size(), 2u);
  for (const ExpectationResult& e : r.expectations) EXPECT_TRUE(e.passed) << e.name << ": " << e.message;
}

}  // namespace
}  // namespace vdrive::scenario
