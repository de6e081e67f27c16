// Scenario files: what a good file holds after loading, and that every kind of mistake is named
// with file, line, column and field.
#include "vdrive/scenario/scenario_loader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace vdrive::scenario {
namespace {

const char* kGood = R"(name: good
description: all parts
seed: 7
duration: 2s
trace_period: 5ms
segment:
  hop_delay: 600ns
  slaves:
    - product: a6b
    - product: ds1000a
master:
  cycle: 500us
  dc: false
  start_state: safeop
  startup:
    - {slave: 1, index: 0x6081, value: 1000}
timeline:
  - {name: go, at: {on: op, delay: 10ms}, enable: {slave: 1, mode: csp}}
  - {at: {on: step, step: go}, motion: {slave: 1, shape: sine, amplitude: 100, frequency: 2, duration: 1s}}
  - {at: 1s, fault: {kind: drop, direction: to_master, probability: 0.25, duration: 20ms, id: loss}}
  - {at: 1200ms, clear_fault: {id: loss}}
  - {at: 1300ms, fault: {kind: alarm, slave: 2, code: FF03h}}
  - {at: 1400ms, target: {slave: 1, position: -5, relative: true}}
expect:
  - {name: enabled, slave: 1, object: 0x6041, mask: 0x6F, equals: 0x27, by: {on: op, delay: 1s}}
  - {slave: 2, al_state: op, always: true, from: {on: op}, until: 1500ms}
  - {slave: 1, register: 0x0300, size: 1, max: 0, at: 1s}
  - {master: wrong_wkc, min: 1, at: {on: step, step: go, delay: 990ms}}
  - {slave: 1, object: 0x6064, near: 100, tolerance: 5, at: 1900ms}
)";

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "t.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ScenarioLoader, AGoodFileKeepsEveryField) {
  const Scenario s = parse_scenario(kGood, "dir/good.yaml");
  EXPECT_EQ(s.name, "good");
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.duration, 2'000'000'000);
  EXPECT_EQ(s.trace_period, 5'000'000);
  EXPECT_EQ(s.hop_delay, 600);
  ASSERT_EQ(s.slaves.size(), 2u);
  EXPECT_EQ(s.slaves[1].product, "ds1000a");
  EXPECT_EQ(s.master.cycle, 500'000);
  EXPECT_FALSE(s.master.dc);
  EXPECT_EQ(s.master.start_state, AlTarget::safeop);
  ASSERT_EQ(s.master.startup.size(), 1u);
  EXPECT_EQ(s.master.startup[0].index, 0x6081);
  ASSERT_EQ(s.steps.size(), 6u);
  EXPECT_EQ(s.steps[0].when.event, EventKind::op);
  EXPECT_EQ(s.steps[0].when.delay, 10'000'000);
  EXPECT_EQ(std::get<EnableAction>(s.steps[0].action).mode, 8);
  EXPECT_EQ(s.steps[1].when.event, EventKind::step);
  EXPECT_EQ(std::get<MotionAction>(s.steps[1].action).shape, MotionAction::Shape::sine);
  const auto& f = std::get<FaultAction>(s.steps[2].action);
  EXPECT_EQ(f.fault.kind, fault::FaultKind::drop);
  EXPECT_EQ(f.fault.direction, fault::WireDirection::to_master);
  EXPECT_DOUBLE_EQ(f.fault.probability, 0.25);
  EXPECT_EQ(f.fault.duration, 20'000'000);
  EXPECT_EQ(f.id, "loss");
  EXPECT_EQ(std::get<ClearFaultAction>(s.steps[3].action).id, "loss");
  EXPECT_EQ(std::get<FaultAction>(s.steps[4].action).fault.alarm, "FF03h");
  EXPECT_EQ(*std::get<TargetAction>(s.steps[5].action).position, -5);
  EXPECT_TRUE(std::get<TargetAction>(s.steps[5].action).relative);
  ASSERT_EQ(s.expectations.size(), 5u);
  EXPECT_EQ(s.expectations[0].timing, Expectation::Timing::by);
  EXPECT_EQ(*s.expectations[0].condition.mask, 0x6F);
  EXPECT_EQ(s.expectations[1].probe.kind, Probe::Kind::al_state);
  EXPECT_EQ(s.expectations[1].timing, Expectation::Timing::always);
  EXPECT_EQ(s.expectations[1].until->delay, 1'500'000'000);
  EXPECT_EQ(s.expectations[2].probe.kind, Probe::Kind::esc_register);
  EXPECT_EQ(s.expectations[2].probe.size, 1);
  EXPECT_EQ(s.expectations[3].probe.kind, Probe::Kind::master_wrong_wkc);
  EXPECT_EQ(s.expectations[1].name, "expect[1] (line 26)");
  EXPECT_EQ(s.expectations[1].line, 26);
}

TEST(ScenarioLoader, MistakesNameFileLineColumnAndField) {
  const std::string head = "duration: 1s\nsegment:\n  slaves:\n    - product: a6b\n";
  EXPECT_EQ(error_of(head + "colour: red\n"), "t.yaml:5:1: colour: unknown key");
  EXPECT_EQ(error_of("segment:\n  slaves: [{product: a6b}]\n"), "t.yaml:1:1: (top): missing \"duration\"");
  EXPECT_EQ(error_of("duration: 10\nsegment: {slaves: [{product: a6b}]}\n"),
            "t.yaml:1:11: duration: expected a time with a unit (e.g. 250ms, 1.5s, 125us), got \"10\"");
  EXPECT_NE(error_of("duration: 1s\nsegment: {slaves: [{product: a7}]}\n").find("segment.slaves[0].product: unknown product \"a7\" (a6b, ds1000a, ds5c1)"),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, fault: {kind: jamm, slave: 1}}\n").find("t.yaml:6:28: timeline[0].fault.kind: unknown fault kind \"jamm\" (drop, corrupt"),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, enable: {slave: 1, mode: csp}, disable: {slave: 1}}\n").find("a step has one action"),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, enable: {slave: 2, mode: csp}}\n").find("timeline[0].enable.slave: 2 is out of range [1, 1]"),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: {on: step, step: nope}, disable: {slave: 1}}\n").find("no step is named \"nope\""),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: {on: lunch}, disable: {slave: 1}}\n").find("unknown event \"lunch\""),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, fault: {kind: drop, probability: 2}}\n").find("timeline[0].fault.probability: must be between 0 and 1"),
            std::string::npos);
  EXPECT_NE(error_of(head + "expect:\n  - {slave: 1, object: 0x6041, at: 1s}\n").find("expect[0]: an expectation needs a condition"),
            std::string::npos);
  EXPECT_NE(error_of(head + "expect:\n  - {slave: 1, object: 0x6041, equals: 1, at: 1s, by: 2s}\n").find("exactly one of at, by or always"),
            std::string::npos);
  EXPECT_NE(error_of(head + "expect:\n  - {slave: 1, al_state: running, at: 1s}\n").find("unknown AL state \"running\""),
            std::string::npos);
  EXPECT_NE(error_of(head + "master: {cycle: 50us}\n").find("master.cycle: the built-in master cycles at 125us or slower"),
            std::string::npos);
  EXPECT_NE(error_of("duration: [1s\n").find("t.yaml:"), std::string::npos);
}

// A misspelt key is named as itself, with the key it was probably meant to be, before anything
// it leaves missing; a misspelt mode gets the mode names.
TEST(ScenarioLoader, TyposAreNamedWithWhatWasMeant) {
  const std::string head = "duration: 1s\nsegment:\n  slaves:\n    - product: a6b\n";
  EXPECT_EQ(error_of("duraton: 1s\nsegment: {slaves: [{product: a6b}]}\n"),
            "t.yaml:1:1: duraton: unknown key \"duraton\", did you mean \"duration\"?");
  EXPECT_EQ(error_of("duration: 1s\nsegmnt: {slaves: [{product: a6b}]}\n"),
            "t.yaml:2:1: segmnt: unknown key \"segmnt\", did you mean \"segment\"?");
  EXPECT_EQ(error_of(head + "timeline:\n  - {at: 1s, enable: {slave: 1, mode: cps}}\n"),
            "t.yaml:6:39: timeline[0].enable.mode: unknown mode \"cps\", did you mean \"csp\"? (pp, pv, tq, hm, ip, "
            "csp, csv, cst, or a 6060h number)");
  EXPECT_EQ(error_of(head + "timeline:\n  - {at: 1s, sdo_wirte: {slave: 1, index: 0x6060, value: 8}}\n"),
            "t.yaml:6:14: timeline[0].sdo_wirte: unknown key \"sdo_wirte\", did you mean \"sdo_write\"?");
  EXPECT_EQ(error_of(head + "expect:\n  - {slave: 1, objcet: 0x6041, equals: 1, at: 1s}\n"),
            "t.yaml:6:16: expect[0].objcet: unknown key \"objcet\", did you mean \"object\"?");
  EXPECT_EQ(error_of(head + "master: {cycle: 1ms, dcc: true}\n"),
            "t.yaml:5:22: master.dcc: unknown key, did you mean \"dc\"?");
}

TEST(ScenarioLoader, LinkDownNamesACableByTheSlaveItLeadsIntoOrByAPort) {
  const std::string head = "duration: 1s\nsegment:\n  slaves:\n    - product: a6b\n    - product: ds5c1\n";
  const Scenario s = parse_scenario(head + "timeline:\n  - {at: 1ms, fault: {kind: link_down, slave: 2}}\n"
                                           "  - {at: 2ms, fault: {kind: link_down, slave: 1, port: 1}}\n", "t.yaml");
  EXPECT_EQ(std::get<FaultAction>(s.steps[0].action).fault.port, 0);
  EXPECT_EQ(std::get<FaultAction>(s.steps[1].action).fault.slave, 1);
  EXPECT_EQ(std::get<FaultAction>(s.steps[1].action).fault.port, 1);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, fault: {kind: link_down, slave: 1, port: 4}}\n").find("timeline[0].fault.port"),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, fault: {kind: jam, slave: 1, port: 1}}\n").find("timeline[0].fault.port: unknown key"),
            std::string::npos);
}

// A fault's slave by position or by the station address the master sets; other values are refused
// at the field.
TEST(ScenarioLoader, AFaultsSlaveIsAPositionOrAStationAddress) {
  const std::string head = "duration: 1s\nsegment:\n  slaves:\n    - product: a6b\n    - product: ds5c1\n";
  const Scenario s = parse_scenario(head + "timeline:\n  - {at: 1ms, fault: {kind: jam, slave: 0x1002}}\n"
                                           "  - {at: 2ms, fault: {kind: jam, slave: 2}}\n", "t.yaml");
  EXPECT_EQ(std::get<FaultAction>(s.steps[0].action).fault.station, 0x1002);
  EXPECT_EQ(std::get<FaultAction>(s.steps[0].action).fault.slave, 0);
  EXPECT_EQ(std::get<FaultAction>(s.steps[1].action).fault.slave, 2);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, fault: {kind: jam, slave: 0x}}\n").find("timeline[0].fault.slave"),
            std::string::npos);
  EXPECT_NE(error_of(head + "timeline:\n  - {at: 1s, fault: {kind: jam, slave: [1]}}\n").find("timeline[0].fault.slave"),
            std::string::npos);
}

TEST(ScenarioLoader, PlantFilesAreReadBesideTheScenario) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("vdrive-scenario-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "plants");
  std::ofstream(dir / "plants" / "p.yaml") << "plant:\n  axes:\n    - {name: a, motor: {product: a6b}, load_inertia_kgm2: 1.0e-4}\n";
  std::ofstream(dir / "s.yaml") << "duration: 1s\nsegment: {slaves: [{product: a6b, plant: plants/p.yaml}]}\n";
  const Scenario s = load_scenario_file((dir / "s.yaml").string());
  ASSERT_TRUE(s.slaves[0].plant);
  EXPECT_EQ(s.slaves[0].plant->axes.size(), 1u);
  std::ofstream(dir / "bad.yaml") << "duration: 1s\nsegment: {slaves: [{product: a6b, plant: plants/none.yaml}]}\n";
  EXPECT_THROW(load_scenario_file((dir / "bad.yaml").string()), ScenarioError);
  EXPECT_EQ(scenario_files(dir.string()).size(), 2u) << "*.yaml directly in the directory, sorted";
  EXPECT_EQ(scenario_files(dir.string())[0], (dir / "bad.yaml").string());
  std::filesystem::remove_all(dir);
  EXPECT_THROW(scenario_files(dir.string()), ScenarioError);
}

}  // namespace
}  // namespace vdrive::scenario
