// Signals through the control channel: named signals of the network file and any point, read,
// set and listed on the loop's thread; what does not exist or does not fit is a bad request
// that names it.
#include "vdrive/control/signal_requests.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/control/fault_service.hpp"

namespace vdrive::control {
namespace {

using ::testing::HasSubstr;
using Op = ControlRequest::Op;

network::NetworkOptions bench() {
  network::NetworkOptions o;
  o.slave_names = {"x", "y"};
  o.signals = {{"mode", network::SignalPoint{0, std::nullopt, 0x6060, 0}, ""},
               {"y_home", network::SignalPoint{1, network::PlantConnection::home, 0, 0}, ""}};
  return o;
}

ControlRequest request(Op op, std::string signal = {}, std::int64_t value = 0) {
  ControlRequest r;
  r.op = op;
  r.signal = std::move(signal);
  r.value = value;
  return r;
}

class SignalRequests : public ::testing::Test {
protected:
  VirtualClock clock_{1'000'000};
  network::Network net_{std::vector<std::string>{"a6b", "ds5c1"}, clock_, bench()};
};

TEST_F(SignalRequests, ListGivesEveryNamedSignalWithPointTypeAndValue) {
  const ControlReply r = handle_signal_request(net_, request(Op::signals));
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.signals.size(), 2u);
  EXPECT_EQ(r.signals[0].name, "mode");
  EXPECT_EQ(r.signals[0].point, "x 0x6060:0");
  EXPECT_EQ(r.signals[0].type, "I8");
  EXPECT_EQ(r.signals[1].name, "y_home");
  EXPECT_EQ(r.signals[1].point, "y.home");
  EXPECT_EQ(r.signals[1].type, "connection");
  EXPECT_EQ(r.signals[1].value, 0);
}

TEST_F(SignalRequests, SetByNameAndReadByPoint) {
  const ControlReply set = handle_signal_request(net_, request(Op::signal_set, "mode", -2));
  ASSERT_TRUE(set.ok()) << set.error;
  ASSERT_EQ(set.signals.size(), 1u);
  EXPECT_EQ(set.signals[0].value, -2) << "the reply carries the value after the write";
  const ControlReply get = handle_signal_request(net_, request(Op::signal_get, "1 0x6060:0"));
  ASSERT_TRUE(get.ok()) << get.error;
  EXPECT_EQ(get.signals[0].name, "1 0x6060:0");
  EXPECT_EQ(get.signals[0].point, "x 0x6060:0");
  EXPECT_EQ(get.signals[0].value, -2);
}

TEST_F(SignalRequests, WhatDoesNotExistOrFitIsABadRequestNamingIt) {
  const ControlReply unknown = handle_signal_request(net_, request(Op::signal_get, "door"));
  EXPECT_EQ(unknown.status, ControlReply::Status::bad_request);
  EXPECT_EQ(unknown.error, "no signal 'door' (signals: mode, y_home) and not a point: 'door': expected SLAVE "
                           "INDEX:SUBINDEX (e.g. 'do 0x7000:1') or SLAVE.CONNECTION (e.g. 'x.home')");
  const ControlReply missing = handle_signal_request(net_, request(Op::signal_get, "y 0x7000:1"));
  EXPECT_EQ(missing.status, ControlReply::Status::bad_request);
  EXPECT_THAT(missing.error, HasSubstr("'y' (slave 2, ds5c1) has no object 7000h:01h"));
  const ControlReply too_big = handle_signal_request(net_, request(Op::signal_set, "y_home", 2));
  EXPECT_EQ(too_big.status, ControlReply::Status::bad_request);
  EXPECT_EQ(too_big.error, "signal 'y_home': 2 is outside 0..1");
}

TEST_F(SignalRequests, TheFaultServiceCarriesThemOut) {
  FaultService service(net_, nullptr, nullptr);
  const ControlReply r = service.handle(request(Op::signal_set, "y.probe1", 1), clock_.now());
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.signals.at(0).value, 1);
  EXPECT_EQ(net_.resolve(net_.parse_point("y.probe1")).read(), 1);
}

}  // namespace
}  // namespace vdrive::control
