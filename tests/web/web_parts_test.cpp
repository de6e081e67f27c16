// The web server's parts on their own: addresses, calls into the loop, the record.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/web/cia402_text.hpp"
#include "vdrive/web/line_record.hpp"
#include "vdrive/web/loop_calls.hpp"
#include "vdrive/web/web_address.hpp"

namespace vdrive::web {
namespace {

TEST(WebAddress, PortAloneIsThisMachineOnly) {
  const WebAddress a = parse_web_address("8080");
  EXPECT_EQ(a.host, "127.0.0.1");
  EXPECT_EQ(a.port, 8080);
  EXPECT_TRUE(a.loopback());
  EXPECT_EQ(a.url(), "http://127.0.0.1:8080/");
}

TEST(WebAddress, OtherAddressesServeOtherMachines) {
  EXPECT_FALSE(parse_web_address("0.0.0.0:80").loopback());
  EXPECT_FALSE(parse_web_address("192.168.1.5:80").loopback());
  EXPECT_TRUE(parse_web_address("localhost:80").loopback());
  EXPECT_TRUE(parse_web_address("[::1]:8080").loopback());
  EXPECT_EQ(parse_web_address("[::1]:8080").host, "::1");
}

TEST(WebAddress, BadAddressesNameTheProblem) {
  for (const char* bad : {"", "0", "65536", "80a", "host:", ":80", "a b:80", "[nope]:80", "1:2:3"}) {
    try {
      (void)parse_web_address(bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(LoopCalls, WorkRunsOnTheLoopThread) {
  LoopCalls calls;
  std::atomic<bool> stop{false};
  std::thread::id loop_id;
  std::thread loop([&] {
    loop_id = std::this_thread::get_id();
    while (!stop.load()) {
      calls.poll(0);
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  });
  std::thread::id ran_on;
  EXPECT_TRUE(calls.run([&](Nanos) { ran_on = std::this_thread::get_id(); }, 1'000'000'000));
  stop.store(true);
  loop.join();
  EXPECT_EQ(ran_on, loop_id);
}

TEST(LoopCalls, WorkTheLoopDidNotStartInTimeNeverRuns) {
  LoopCalls calls;
  bool ran = false;
  EXPECT_FALSE(calls.run([&](Nanos) { ran = true; }, 5'000'000));
  calls.poll(0);  // the loop comes back after the caller gave up
  EXPECT_FALSE(ran);
}

TEST(LineRecord, EventsAreNumberedFilteredAndQuotedInCsv) {
  LineRecord record({}, LineIdentity{"test", "veth0", "1", false}, 0);
  record.note(1, "od_write", 0, 0, "6060h:00 := 8", 10);
  record.note(2, "scenario", 0, 0, "say \"hi\", twice", 20);
  const nlohmann::json all = record.events(0, "", 0);
  ASSERT_EQ(all["events"].size(), 2u);
  EXPECT_EQ(all["seq"], 2);
  EXPECT_EQ(record.events(1, "", 0)["events"].size(), 1u);
  EXPECT_EQ(record.events(0, "od_write", 0)["events"].size(), 1u);
  EXPECT_EQ(record.events(0, "", 2)["events"][0]["kind"], "scenario");
  EXPECT_NE(record.events_csv("", 0).find("\"say \"\"hi\"\", twice\""), std::string::npos);
}

TEST(LineRecord, KeepsTheLastEventsOnly) {
  LineRecord record({}, LineIdentity{}, 0);
  for (std::size_t i = 0; i < LineRecord::kEvents + 10; ++i) record.note(0, "x", 0, 0, "", 0);
  const nlohmann::json all = record.events(0, "", 0);
  EXPECT_EQ(all["events"].size(), LineRecord::kEvents);
  EXPECT_EQ(all["events"][0]["seq"], 11);
}

TEST(Cia402Text, StatewordsAndModesInWords) {
  EXPECT_EQ(pds_state_name(0x0250), "Switch on disabled");
  EXPECT_EQ(pds_state_name(0x1237), "Operation enabled");
  EXPECT_EQ(pds_state_name(0x0218), "Fault");
  EXPECT_EQ(pds_state_name(0x0207), "Quick stop active");
  EXPECT_EQ(mode_name(8), "csp");
  EXPECT_EQ(mode_name(-1), "mode -1");
}


TEST(LoopCalls, AClosedLoopAnswersAtOnce) {
  LoopCalls calls;
  calls.close();
  const auto start = std::chrono::steady_clock::now();
  bool ran = false;
  // Without close() this would wait the whole 30 s; the bound is far from any scheduling noise.
  EXPECT_FALSE(calls.run([&](Nanos) { ran = true; }, 30'000'000'000));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  calls.poll(0);
  EXPECT_FALSE(ran);
}


TEST(LineRecord, AScenarioIsDecidedOnceEveryExpectationIs) {
  LineRecord record({}, LineIdentity{}, 0);
  ScenarioView v;
  v.name = "s";
  v.duration = 3'000'000'000;
  v.started = 1'000'000'000;
  v.expectations = {{1, "a", "open", ""}, {2, "b", "open", ""}};
  record.set_scenario(v);
  nlohmann::json s = record.line(1'500'000'000)["scenario"];
  EXPECT_EQ(s["state"], "running");
  EXPECT_EQ(s["elapsed_ns"], 500'000'000) << "from the line's clock, not only the runner's whole seconds";
  record.update_scenario([](ScenarioView& x) { x.expectations[0].state = "met"; });
  EXPECT_EQ(record.line(2'000'000'000)["scenario"]["state"], "running");
  record.update_scenario([](ScenarioView& x) { x.expectations[1].state = "missed"; });
  s = record.line(9'000'000'000)["scenario"];
  EXPECT_EQ(s["state"], "failed");
  EXPECT_EQ(s["elapsed_ns"], 3'000'000'000) << "never past the duration";
}


TEST(LineRecord, AnAlarmValueSeveralAlarmsShareNamesThemAll) {
  const profile::ProductProfile a6b = profile::load_profile("a6b");
  SlaveInfo s;
  s.position = 1;
  s.product = "a6b";
  s.drive = true;
  s.profile = &a6b;
  LineRecord record({s}, LineIdentity{}, 0);
  telemetry::EventSample shared;
  shared.slave = 1;
  shared.kind = telemetry::EventKind::alarm_raised;
  shared.value = 0xFF1B;  // 27.1, 27.4, 27.6 and 27.7
  record.add(shared);
  telemetry::EventSample single = shared;
  single.value = 0xFF0C;  // 12.0 only
  record.add(single);
  const nlohmann::json events = record.events(0, "alarm_raised", 0)["events"];
  ASSERT_EQ(events.size(), 2u);
  EXPECT_NE(events[0]["text"].get<std::string>().find("one of 27.1, 27.4, 27.6, 27.7"), std::string::npos) << events[0]["text"];
  EXPECT_NE(events[1]["text"].get<std::string>().find("12.0 "), std::string::npos) << events[1]["text"];
}


TEST(LineRecord, AnSdoAbortAMasterGotIsAnEvent) {
  SlaveInfo s;
  s.position = 1;
  LineRecord record({s}, LineIdentity{}, 0);
  std::vector<SlaveRegisters> r(1);
  r[0].sdo_aborts = 3;  // before the page: the baseline
  record.set_registers(r, 10);
  EXPECT_TRUE(record.events(0, "sdo_abort", 0)["events"].empty());
  r[0].sdo_aborts = 5;
  r[0].abort_index = 0x6041;
  r[0].abort_code = 0x06010002;
  record.set_registers(r, 20);
  const nlohmann::json e = record.events(0, "sdo_abort", 0)["events"];
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0]["slave"], 1);
  EXPECT_EQ(e[0]["text"], "6041h:00 abort 0x06010002 Attempt to write a read-only object (the last of 2)");
}

}  // namespace
}  // namespace vdrive::web
