// The control protocol's JSON lines: valid requests, every refusal names what was wrong, and
// replies survive the trip to the client.
#include "vdrive/control/control_protocol.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vdrive::control {
namespace {

using ::testing::HasSubstr;
using Op = ControlRequest::Op;

std::string refusal(std::string_view line) {
  try {
    parse_request(line);
  } catch (const ProtocolError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ControlProtocol, InjectWithScenarioFieldsAndTimes) {
  const ControlRequest r =
      parse_request(R"({"op":"inject","fault":{"kind":"drop","probability":0.5,"duration":"100ms","direction":"to_master"}})");
  EXPECT_EQ(r.op, Op::inject);
  EXPECT_EQ(r.fault.kind, fault::FaultKind::drop);
  EXPECT_DOUBLE_EQ(r.fault.probability, 0.5);
  EXPECT_EQ(r.fault.duration, 100'000'000);
  EXPECT_EQ(r.fault.direction, fault::WireDirection::to_master);
}

TEST(ControlProtocol, InjectDefaultsAreTheScenarioDefaults) {
  const ControlRequest r = parse_request(R"({"op":"inject","fault":{"kind":"drop"}})");
  EXPECT_DOUBLE_EQ(r.fault.probability, 1.0);
  EXPECT_EQ(r.fault.duration, 0);
  EXPECT_EQ(r.fault.direction, fault::WireDirection::both);
}

TEST(ControlProtocol, PerKindFields) {
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"delay","delay":"2ms"}})").fault.delay, 2'000'000);
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"lost_reply","slave":2,"count":3}})").fault.count, 3);
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"sdo_abort","slave":1,"abort_code":"0x06020000"}})").fault.abort_code,
            0x06020000u);
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"sdo_abort","slave":1,"abort_code":134348800}})").fault.abort_code,
            0x08020000u);
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"alarm","slave":1,"code":"Er16.0"}})").fault.alarm, "Er16.0");
  const ControlRequest lc = parse_request(R"({"op":"inject","fault":{"kind":"load_change","slave":1,"load_scale":2.5,"force":-3}})");
  EXPECT_DOUBLE_EQ(lc.fault.load_scale, 2.5);
  EXPECT_DOUBLE_EQ(lc.fault.friction_scale, 1.0) << "friction as it was unless asked";
  EXPECT_DOUBLE_EQ(parse_request(R"({"op":"inject","fault":{"kind":"load_change","slave":1,"friction_scale":3}})").fault.friction_scale, 3.0);
  EXPECT_DOUBLE_EQ(lc.fault.force, -3.0);
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"link_down","slave":2,"duration":"1s"}})").fault.slave, 2);
  const ControlRequest at_port = parse_request(R"({"op":"inject","fault":{"kind":"link_down","slave":1,"port":3}})");
  EXPECT_EQ(at_port.fault.slave, 1);
  EXPECT_EQ(at_port.fault.port, 3);
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"link_down","slave":2}})").fault.port, 0) << "the cable into it";
}

// "slave": a position (number or text) or a station address as text, found when the fault starts.
TEST(ControlProtocol, ASlaveIsAPositionOrAStationAddress) {
  const ControlRequest by_address = parse_request(R"({"op":"inject","fault":{"kind":"overload","slave":"0x1002"}})");
  EXPECT_EQ(by_address.fault.station, 0x1002);
  EXPECT_EQ(by_address.fault.slave, 0) << "found by the injector";
  EXPECT_EQ(parse_request(R"({"op":"inject","fault":{"kind":"overload","slave":"2"}})").fault.slave, 2);
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"overload","slave":"0"}})"), HasSubstr("positions count from 1"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"overload","slave":"second"}})"), HasSubstr("'second' names no slave"));
}

TEST(ControlProtocol, PortIsLinkDownsOnly) {
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"link_down","slave":1,"port":4}})"), HasSubstr("\"port\""));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"jam","slave":1,"port":1}})"), HasSubstr("\"port\""));
}

TEST(ControlProtocol, OtherOps) {
  EXPECT_EQ(parse_request(R"({"op":"list"})").op, Op::list);
  EXPECT_EQ(parse_request(R"({"op":"clear_all"})").op, Op::clear_all);
  const ControlRequest c = parse_request(R"({"op":"clear","id":3})");
  EXPECT_EQ(c.op, Op::clear);
  EXPECT_EQ(c.id, 3);
}

// Part 1 of `vdrive run --processes` asks the other parts which slave has an address.
TEST(ControlProtocol, FindStation) {
  const ControlRequest r = parse_request(R"({"op":"find_station","station":"0x1003"})");
  EXPECT_EQ(r.op, Op::find_station);
  EXPECT_EQ(r.station, 0x1003);
  EXPECT_EQ(parse_request(R"({"op":"find_station","station":4099})").station, 0x1003);
  EXPECT_THAT(refusal(R"({"op":"find_station"})"), HasSubstr("\"station\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"find_station","station":"0x10000"})"), HasSubstr("expected a station address 0x0001..0xFFFF"));
  EXPECT_THAT(refusal(R"({"op":"find_station","station":0})"), HasSubstr("expected a station address"));
  ControlReply found;
  found.slave = 3;
  EXPECT_EQ(parse_reply(format_reply(found)).slave, 3);
  EXPECT_EQ(format_reply(ControlReply{}).find("slave"), std::string::npos);  // no slave: not in the reply
}

TEST(ControlProtocol, SignalOps) {
  EXPECT_EQ(parse_request(R"({"op":"signals"})").op, Op::signals);
  const ControlRequest get = parse_request(R"({"op":"signal_get","signal":"di 0x6000:1"})");
  EXPECT_EQ(get.op, Op::signal_get);
  EXPECT_EQ(get.signal, "di 0x6000:1");
  const ControlRequest set = parse_request(R"({"op":"signal_set","signal":"door","value":-7})");
  EXPECT_EQ(set.op, Op::signal_set);
  EXPECT_EQ(set.signal, "door");
  EXPECT_EQ(set.value, -7);
  EXPECT_EQ(parse_request(R"({"op":"signal_set","signal":"x.home","value":true})").value, 1);
  EXPECT_THAT(refusal(R"({"op":"signal_get"})"), HasSubstr("\"signal\" must name a signal"));
  EXPECT_THAT(refusal(R"({"op":"signal_set","signal":"door"})"), HasSubstr("\"value\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"signal_set","signal":"door","value":"1"})"),
              HasSubstr("\"value\": expected an integer or true/false, got \"1\""));
  EXPECT_THAT(refusal(R"({"op":"signal_get","signal":"door","value":1})"),
              HasSubstr("\"value\" does not belong in a \"signal_get\" request"));
}

TEST(ControlProtocol, SignalRepliesComeBackAsSent) {
  ControlReply reply;
  reply.signals.push_back({"door", "di 0x6000:2", "BOOL", 1});
  reply.signals.push_back({"x 0x6060:0", "x 0x6060:0", "I8", -3});
  const ControlReply back = parse_reply(format_reply(reply));
  ASSERT_EQ(back.signals.size(), 2u);
  EXPECT_EQ(back.signals[0].name, "door");
  EXPECT_EQ(back.signals[0].point, "di 0x6000:2");
  EXPECT_EQ(back.signals[0].type, "BOOL");
  EXPECT_EQ(back.signals[0].value, 1);
  EXPECT_EQ(back.signals[1].value, -3);
}

TEST(ControlProtocol, RefusalsNameWhatWasWrong) {
  EXPECT_THAT(refusal("{"), HasSubstr("not a JSON request"));
  EXPECT_THAT(refusal(R"({"op":1E999})"), HasSubstr("not a JSON request"));  // too large for a double
  EXPECT_THAT(refusal("[1]"), HasSubstr("JSON object"));
  EXPECT_THAT(refusal(R"({"op":"explode"})"), HasSubstr("unknown op \"explode\""));
  EXPECT_THAT(refusal(R"({"fault":{}})"), HasSubstr("\"op\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"list","id":1})"), HasSubstr("\"id\" does not belong in a \"list\" request"));
  EXPECT_THAT(refusal(R"({"op":"clear"})"), HasSubstr("\"id\""));
  EXPECT_THAT(refusal(R"({"op":"clear","id":0})"), HasSubstr("\"id\""));
  EXPECT_THAT(refusal(R"({"op":"inject"})"), HasSubstr("\"fault\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"wobble"}})"), HasSubstr("unknown fault kind \"wobble\" (drop, corrupt"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"probability":1}})"), HasSubstr("\"kind\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"drop","probability":1.5}})"),
              HasSubstr("\"probability\": 1.5 must be between 0 and 1"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"drop","probability":"high"}})"), HasSubstr("expected a number"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"drop","duration":"100"}})"),
              HasSubstr("\"duration\": \"100\" is not a time with a unit"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"drop","duration":100}})"), HasSubstr("expected a string"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"drop","direction":"up"}})"), HasSubstr("unknown direction \"up\""));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"drop","slave":1}})"),
              HasSubstr("\"slave\" does not apply to kind \"drop\""));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"drop","colour":"red"}})"), HasSubstr("\"colour\" does not apply"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"overload"}})"), HasSubstr("\"slave\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"overload","slave":0}})"), HasSubstr("out of range"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"delay"}})"), HasSubstr("\"delay\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"alarm","slave":1}})"), HasSubstr("\"code\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"collision","slave":1}})"), HasSubstr("\"position\" is missing"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"load_change","slave":1,"load_scale":0}})"), HasSubstr("must be > 0"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"load_change","slave":1,"friction_scale":-0.5}})"),
              HasSubstr("friction_scale\": -0.5 must be >= 0"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"sdo_abort","slave":1,"abort_code":"0xZZ"}})"),
              HasSubstr("is not an integer"));
  EXPECT_THAT(refusal(R"({"op":"inject","fault":{"kind":"toggle_error","slave":1,"duration":"1s"}})"),
              HasSubstr("\"duration\" does not apply"));  // one-shot
}

TEST(ControlProtocol, RepliesRoundTrip) {
  ControlReply r;
  r.id = 4;
  r.faults.push_back({4, "drop", "drop both ways p=1", 5'000'000, 95'000'000});
  r.faults.push_back({5, "delay", "delay 2000000 ns", 1, -1});
  const ControlReply back = parse_reply(format_reply(r));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back.id, 4);
  ASSERT_EQ(back.faults.size(), 2u);
  EXPECT_EQ(back.faults[0].description, "drop both ways p=1");
  EXPECT_EQ(back.faults[0].remaining, 95'000'000);
  EXPECT_EQ(back.faults[1].remaining, -1);
  EXPECT_THAT(format_reply(r), HasSubstr(R"("remaining_ns":null)"));

  const ControlReply e = parse_reply(format_reply(error_reply(ControlReply::Status::bad_request, "no active fault 9")));
  EXPECT_EQ(e.status, ControlReply::Status::bad_request);
  EXPECT_EQ(e.error, "no active fault 9");
  EXPECT_EQ(parse_reply(format_reply(error_reply(ControlReply::Status::denied, "x"))).status, ControlReply::Status::denied);
  EXPECT_THROW(parse_reply("garbage"), ProtocolError);
}

}  // namespace
}  // namespace vdrive::control

namespace vdrive::control {
namespace {

TEST(ControlProtocol, BadBytesInARequestStillGetAJsonReply) {
  std::string message;
  try {
    parse_request("{\"op\":\"\xff\xfe\"}");
  } catch (const ProtocolError& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty());
  const std::string line = format_reply(error_reply(ControlReply::Status::bad_request, message));
  EXPECT_EQ(parse_reply(line).status, ControlReply::Status::bad_request);
}

TEST(ControlProtocol, LineStatusCarriesEachSlavesAlStateAndErrors) {
  EXPECT_EQ(parse_request(R"({"op":"line_status"})").op, ControlRequest::Op::line_status);
  EXPECT_THAT(refusal(R"({"op":"line_status","slave":1})"), HasSubstr("\"slave\" does not belong in a \"line_status\" request"));
  ControlReply reply;
  reply.states = {{0x08, 0, 0}, {0x14, 0x001B, 3}};
  const ControlReply back = parse_reply(format_reply(reply));
  ASSERT_EQ(back.states.size(), 2u);
  EXPECT_EQ(back.states[1].al_status, 0x14);
  EXPECT_EQ(back.states[1].al_status_code, 0x001B);
  EXPECT_EQ(back.states[1].rx_errors, 3u);
  EXPECT_TRUE(parse_reply(format_reply(ControlReply{})).states.empty());
}

}  // namespace
}  // namespace vdrive::control
