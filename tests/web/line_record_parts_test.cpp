// LineRecord in part 1 of a line over processes: the later parts' slaves, points and events, as
// their own pages gave them, in whole-line positions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "vdrive/web/line_record.hpp"

namespace vdrive::web {
namespace {

using json = nlohmann::json;

// Part 1 serves two slaves; part 2 (first index 2) serves two more.
LineRecord two_and_two() {
  std::vector<SlaveInfo> own(2);
  own[0].position = 1;
  own[1].position = 2;
  own[1].parent = 1;
  own[1].parent_port = 1;
  return LineRecord(own, LineIdentity{"run", "veth0", "1", false}, 0, 2);
}

// A slave as a part's own page shows it (positions its own).
json part_slave(int position, std::uint16_t address, bool drive) {
  json s = {{"position", position}, {"name", ""}, {"product", "ds1000a"}, {"address", address}, {"al_state", 8},
            {"al_state_name", "Op"}, {"rx_errors", {1, 0, 0, 0}}, {"lost_links", {0, 2, 0, 0}},
            {"parent", position - 1}, {"parent_port", position == 1 ? 0 : 1}, {"answers", true}};
  s["drive"] = drive ? json{{"state", "Operation enabled"}} : json(nullptr);
  return s;
}

json part_line() {
  return {{"slaves", {part_slave(1, 0x1003, true), part_slave(2, 0x1004, false)}},
          {"counters", {{"host_stalls", 3}, {"longest_host_stall_ns", 4'000'000}}}};
}

TEST(LineRecordParts, LaterSlavesFollowWithWholeLinePositionsAndCables) {
  LineRecord record = two_and_two();
  EXPECT_EQ(record.size(), 4u);
  EXPECT_TRUE(record.served_here(1));
  EXPECT_FALSE(record.served_here(2));
  record.set_part_line(2, part_line());
  const json line = record.line(0);
  ASSERT_EQ(line["slaves"].size(), 4u);
  const json& third = line["slaves"][2];
  EXPECT_EQ(third["position"], 3);
  EXPECT_EQ(third["parent"], 2) << "the part's first slave hangs on the slave before the part";
  EXPECT_EQ(third["parent_port"], 1);
  EXPECT_EQ(third["address"], 0x1003);
  EXPECT_EQ(third["answers"], true);
  EXPECT_EQ(line["slaves"][3]["position"], 4);
  EXPECT_EQ(line["slaves"][3]["parent"], 3);
  EXPECT_EQ(line["counters"]["rx_errors"], 2) << "each later slave's port counters count";
  EXPECT_EQ(line["counters"]["lost_links"], 4);
  EXPECT_EQ(line["counters"]["host_stalls"], 3);
  EXPECT_EQ(line["counters"]["longest_host_stall_ns"], 4'000'000);
  EXPECT_EQ(record.stations(), (std::vector<std::uint16_t>{0, 0, 0x1003, 0x1004}));
}

TEST(LineRecordParts, BeforeItsPartAnswersASlaveIsThereWithNothingKnown) {
  const json line = two_and_two().line(0);
  ASSERT_EQ(line["slaves"].size(), 4u);
  EXPECT_EQ(line["slaves"][3]["position"], 4);
  EXPECT_EQ(line["slaves"][3]["answers"], false);
  EXPECT_EQ(line["slaves"][3]["al_state_name"], "no answer");
  EXPECT_TRUE(line["slaves"][3]["drive"].is_null());
}

TEST(LineRecordParts, PointsOfALaterAxisGetThisRecordsSequence) {
  LineRecord record = two_and_two();
  record.set_part_line(2, part_line());
  const json samples = json::parse(R"({"seq": 7, "axes": [{"slave": 1, "t": [0.5, 0.52], "target_position": [10, 20],
      "position": [9, 19], "velocity": [1, 2], "torque": [3, -4], "following_error": [1, 1]}]})");
  record.add_part_samples(2, samples);
  const json all = record.samples(0, 0);
  EXPECT_EQ(all["seq"], 2) << "numbered here, not by the part";
  ASSERT_EQ(all["axes"].size(), 1u) << "part 1's slaves have no drive here; slave 4 none either";
  EXPECT_EQ(all["axes"][0]["slave"], 3);
  EXPECT_EQ(all["axes"][0]["position"], json({9, 19}));
  EXPECT_EQ(all["axes"][0]["torque"], json({3, -4}));
  EXPECT_DOUBLE_EQ(all["axes"][0]["t"][1].get<double>(), 0.52);
  EXPECT_EQ(record.samples(1, 3)["axes"][0]["position"], json({19}));
}

TEST(LineRecordParts, EventsOfALaterPartNameWholeLineSlaves) {
  LineRecord record = two_and_two();
  record.note(1, "od_write", 0, 0, "here", 5);
  const json events = json::parse(R"({"seq": 12, "events": [
      {"seq": 11, "time_ns": 900, "slave": 2, "kind": "alarm_raised", "value": 65285, "previous": 0,
       "text": "alarm 16.0 at slave 2"},
      {"seq": 12, "time_ns": 950, "slave": 0, "kind": "host_stall", "value": 1, "previous": 0,
       "text": "host stall 3.1 ms (threshold 2.0 ms): slaves 1-2 missed 2 SYNC0 pulses, drive 1 caught up 9 control steps"}]})");
  record.add_part_events(2, events);
  const json all = record.events(0, "", 0);
  ASSERT_EQ(all["events"].size(), 3u);
  EXPECT_EQ(all["events"][1]["seq"], 2);
  EXPECT_EQ(all["events"][1]["slave"], 4);
  EXPECT_EQ(all["events"][1]["time_ns"], 900);
  EXPECT_EQ(all["events"][1]["text"], "alarm 16.0 at slave 4");
  EXPECT_EQ(all["events"][2]["slave"], 0) << "a line-wide event stays line-wide";
  EXPECT_EQ(all["events"][2]["text"], "host stall 3.1 ms (threshold 2.0 ms): slaves 3-4 missed 2 SYNC0 pulses, drive 3 caught up 9 control steps")
      << "a stall's lists of slaves move too";
}

TEST(LineRecordParts, APartThatStopsAnsweringKeepsItsSlavesMarked) {
  LineRecord record = two_and_two();
  record.set_part_line(2, part_line());
  record.set_part_silent(2, 2, "part 2 (slaves 3-4) does not answer", 77);
  const json line = record.line(0);
  EXPECT_EQ(line["slaves"][2]["answers"], false);
  EXPECT_EQ(line["slaves"][2]["al_state_name"], "no answer");
  EXPECT_EQ(line["slaves"][2]["address"], 0x1003) << "its last view stays";
  const json e = record.events(0, "part_silent", 0)["events"];
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0]["slave"], 3);
  EXPECT_EQ(e[0]["text"], "part 2 (slaves 3-4) does not answer");
}

TEST(LineRecordParts, ALineOfAnotherShapeIsAnErrorNotAGuess) {
  LineRecord record = two_and_two();
  EXPECT_THROW(record.set_part_line(2, json{{"slaves", json::array()}}), json::exception);
  EXPECT_THROW(record.add_part_events(2, json::parse(R"({"events": [{"slave": "x"}]})")), json::exception);
  EXPECT_EQ(record.line(0)["slaves"][2]["answers"], false);
}

}  // namespace
}  // namespace vdrive::web
