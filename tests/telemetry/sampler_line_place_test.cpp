// Sampler in a part of a line cut over processes (Sampler::set_place): its samples and events
// name slaves by whole-line position and faults by run-wide id; part 1 refuses a plant change for
// a slave another part serves, naming why.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vdrive/control/fault_service.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/telemetry/sampler.hpp"

namespace vdrive::telemetry {
namespace {

using ::testing::HasSubstr;

struct Drained {
  std::vector<AxisSample> axes;
  std::vector<BusSample> buses;
  std::vector<EventSample> events;
};

Drained drain(Sampler& s) {
  Drained d;
  while (std::optional<Sample> x = s.pop()) {
    if (const auto* a = std::get_if<AxisSample>(&*x)) d.axes.push_back(*a);
    if (const auto* b = std::get_if<BusSample>(&*x)) d.buses.push_back(*b);
    if (const auto* e = std::get_if<EventSample>(&*x)) d.events.push_back(*e);
  }
  return d;
}

// Part 2 of 2, serving slaves 3 and 4 of the line.
TEST(SamplerLinePlace, ALaterPartNamesItsSlavesAndFaultsAsTheWholeLineDoes) {
  VirtualClock clock{0};
  network::Network net{std::vector<std::string>{"a6b", "ds5c1"}, clock};
  control::FaultService faults(net, nullptr, nullptr);
  Sampler s(net, 100.0, SamplerSources{nullptr, nullptr, &faults.injector()});
  s.set_place(LinePlace{.slaves_before = 2, .part = 1, .parts = 2});
  s.set_fault_handler([&faults](const control::ControlRequest& r, Nanos now) { return faults.handle(r, now); });
  s.poll(0);
  // The part's own slave 1 (the line's slave 3), its own fault 1 (the run's fault 2).
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"inject","fault":{"kind":"encoder_error","slave":1}})")));
  s.poll(1'000'000);
  const std::optional<TelemetryReply> injected = s.reply();
  ASSERT_TRUE(injected);
  ASSERT_TRUE(injected->reply.ok()) << injected->reply.error;
  s.poll(10'000'000);
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"clear","id":1})")));
  s.poll(11'000'000);
  ASSERT_TRUE(s.reply());
  s.poll(20'000'000);
  const Drained d = drain(s);

  ASSERT_FALSE(d.axes.empty());
  for (const AxisSample& a : d.axes) EXPECT_TRUE(a.slave == 3 || a.slave == 4) << a.slave;
  for (const BusSample& b : d.buses) EXPECT_TRUE(b.slave == 3 || b.slave == 4) << b.slave;
  bool started = false, ended = false;
  for (const EventSample& e : d.events) {
    if (e.kind == EventKind::fault_injected) {
      started = true;
      EXPECT_EQ(e.slave, 3);
      EXPECT_EQ(e.value, 2u);
      EXPECT_STREQ(e.text.data(), "fault 2 encoder_error started");
    }
    if (e.kind == EventKind::fault_cleared) {
      ended = true;
      EXPECT_EQ(e.value, 2u);
      EXPECT_STREQ(e.text.data(), "fault 2 ended");
    }
    if (e.kind == EventKind::alarm_raised) {
      EXPECT_EQ(e.slave, 3);
    }
  }
  EXPECT_TRUE(started);
  EXPECT_TRUE(ended);
}

// Part 1 of 2, serving slaves 1 and 2 of a line of 3.
TEST(SamplerLinePlace, PartOneRefusesAPlantChangeForAnotherPartsSlaveNamingWhy) {
  VirtualClock clock{0};
  network::Network net{std::vector<std::string>{"a6b", "ds5c1"}, clock};
  Sampler s(net, 100.0);
  s.set_place(LinePlace{.slaves_before = 0, .part = 0, .parts = 2, .slaves_after = 1});
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"plant_set","slave":3,"external_load":0.5})")));
  s.poll(0);
  std::optional<TelemetryReply> reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->reply.status, control::ControlReply::Status::bad_request);
  EXPECT_THAT(reply->reply.error, HasSubstr("slave 3 is served by another process of this run"));
  EXPECT_THAT(reply->reply.error, HasSubstr("plant changes reach slaves 1-2 only"));
  // Beyond the whole line: no such slave, as in one process.
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"plant_set","slave":4,"external_load":0.5})")));
  s.poll(1'000'000);
  reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_THAT(reply->reply.error, HasSubstr("no slave 4"));
  // Its own slaves are numbered as before.
  const Drained d = drain(s);
  ASSERT_FALSE(d.axes.empty());
  EXPECT_EQ(d.axes.front().slave, 1);
}

}  // namespace
}  // namespace vdrive::telemetry
