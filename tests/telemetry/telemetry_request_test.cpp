// The control topic's request lines: plant_set read here, the rest by the control protocol.
#include "vdrive/telemetry/telemetry_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "vdrive/control/control_protocol.hpp"

namespace vdrive::telemetry {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& line) {
  try {
    parse_telemetry_request(line);
  } catch (const control::ProtocolError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(TelemetryRequest, PlantSet) {
  const TelemetryRequest r = parse_telemetry_request(R"({"op":"plant_set","slave":2,"external_load":-1.5})");
  EXPECT_EQ(r.kind, TelemetryRequest::Kind::plant_set);
  EXPECT_EQ(r.plant.slave, 2);
  EXPECT_DOUBLE_EQ(r.plant.external_load, -1.5);
}

TEST(TelemetryRequest, FaultRequestsAreTheControlProtocols) {
  TelemetryRequest r = parse_telemetry_request(R"({"op":"inject","fault":{"kind":"drop","probability":0.5,"duration":"100ms"}})");
  EXPECT_EQ(r.kind, TelemetryRequest::Kind::fault);
  EXPECT_EQ(r.fault.op, control::ControlRequest::Op::inject);
  EXPECT_DOUBLE_EQ(r.fault.fault.probability, 0.5);
  EXPECT_EQ(r.fault.fault.duration, 100'000'000);
  r = parse_telemetry_request(R"({"op":"clear","id":3})");
  EXPECT_EQ(r.fault.op, control::ControlRequest::Op::clear);
  EXPECT_EQ(r.fault.id, 3);
}

TEST(TelemetryRequest, APlantIsNamedByPositionOrStationAddress) {
  TelemetryRequest r = parse_telemetry_request(R"({"op":"plant_set","slave":2,"external_load":0.5})");
  EXPECT_EQ(r.plant.slave, 2);
  EXPECT_EQ(r.plant.station, 0);
  r = parse_telemetry_request(R"({"op":"plant_set","slave":"0x1002","external_load":-1.5})");
  EXPECT_EQ(r.plant.slave, 0);
  EXPECT_EQ(r.plant.station, 0x1002);
  EXPECT_DOUBLE_EQ(r.plant.external_load, -1.5);
}

TEST(TelemetryRequest, MistakesAreNamed) {
  EXPECT_THAT(error_of("not json"), HasSubstr("not a JSON object"));
  EXPECT_THAT(error_of("[1,2]"), HasSubstr("not a JSON object"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","external_load":1})"), HasSubstr("'slave' is missing"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","slave":0,"external_load":1})"),
              HasSubstr("'slave' must be a position (1 = first in cable order) or a station address such as 0x1001, not 0"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","slave":"1","external_load":1})"), HasSubstr("'slave' must be a position"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","slave":"0x10G2","external_load":1})"), HasSubstr("'0x10G2' names no slave"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","slave":"0x0","external_load":1})"), HasSubstr("station address 0x0000 is no slave's"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","slave":1})"), HasSubstr("'external_load' is missing"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","slave":1,"external_load":"heavy"})"), HasSubstr("'external_load' must be a finite number"));
  EXPECT_THAT(error_of(R"({"op":"plant_set","slave":1,"external_load":1,"inertia":2})"), HasSubstr("unexpected field 'inertia'"));
  EXPECT_THAT(error_of(R"({"op":"inject","fault":{"kind":"nope"}})"), HasSubstr("nope"));
}

}  // namespace
}  // namespace vdrive::telemetry
