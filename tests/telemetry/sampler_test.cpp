// Sampler on the loop thread, in virtual time: rate decimation, no burst after a late loop, a
// full queue drops and counts (never blocks), events (AL state, faults, plant_set), and control
// requests carried out through the queues.
#include "vdrive/telemetry/sampler.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "plant/plant.hpp"
#include "tests/support/station_addresses.hpp"
#include "vdrive/control/fault_service.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::telemetry {
namespace {

using ::testing::HasSubstr;

class SamplerTest : public ::testing::Test {
protected:
  // Everything queued, by kind.
  void drain(Sampler& s) {
    while (std::optional<Sample> x = s.pop()) {
      if (const auto* a = std::get_if<AxisSample>(&*x)) axes.push_back(*a);
      if (const auto* b = std::get_if<BusSample>(&*x)) buses.push_back(*b);
      if (const auto* e = std::get_if<EventSample>(&*x)) events.push_back(*e);
    }
  }
  // Polls every 1 ms from `from` to `to` (exclusive), as a loop serving 1 ms frames would.
  void run(Sampler& s, Nanos from, Nanos to) {
    for (Nanos t = from; t < to; t += 1'000'000) s.poll(t);
  }

  VirtualClock clock_{0};
  network::Network net_{std::vector<std::string>{"a6b", "ds5c1"}, clock_};
  runtime::LoopCounters counters_;
  std::vector<AxisSample> axes;
  std::vector<BusSample> buses;
  std::vector<EventSample> events;
};

TEST_F(SamplerTest, RejectsRatesOutsideItsRange) {
  EXPECT_THROW(Sampler(net_, 0.0), std::invalid_argument);
  EXPECT_THROW(Sampler(net_, -5.0), std::invalid_argument);
  EXPECT_THROW(Sampler(net_, kMaxRateHz * 2), std::invalid_argument);
  EXPECT_EQ(Sampler(net_, kMaxRateHz).period(), 125'000);
}

TEST_F(SamplerTest, SamplesEachAxisAtTheConfiguredRate) {
  Sampler s(net_, 100.0, SamplerSources{&counters_, nullptr, nullptr});
  run(s, 0, 1'000'000'000);  // 1000 polls in 1 s
  drain(s);
  ASSERT_EQ(axes.size(), 2u * 100u);
  ASSERT_EQ(buses.size(), 2u * 100u);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    EXPECT_EQ(axes[i].slave, i % 2 + 1);
    EXPECT_EQ(axes[i].time, static_cast<Nanos>(i / 2) * 10'000'000);
  }
  EXPECT_EQ(s.dropped(), 0u);
  // The drives' own values: Init, 6041h as the drive has it, the plant's temperatures.
  EXPECT_EQ(axes[0].al_state & 0x0F, 1);
  EXPECT_FALSE(std::isnan(axes[0].winding_c));
  EXPECT_GT(axes[0].winding_c, 0.0);
}

TEST_F(SamplerTest, ALateLoopSkipsSamplesInsteadOfBursting) {
  Sampler s(net_, 100.0);
  s.poll(0);
  s.poll(35'000'000);  // 3.5 periods late
  s.poll(36'000'000);
  drain(s);
  ASSERT_EQ(axes.size(), 2u * 2u);
  EXPECT_EQ(axes[2].time, 35'000'000);
  EXPECT_EQ(s.next_deadline(), 45'000'000);
}

TEST_F(SamplerTest, AFullQueueDropsAndCountsWithoutBlocking) {
  Sampler s(net_, 1000.0);
  // 4 samples per period (2 axes + 2 bus) -> 1100 periods queue 4400 into 4096 slots.
  for (Nanos t = 0; t < 1'100'000'000; t += 1'000'000) s.poll(t);
  EXPECT_EQ(s.dropped(), 4u * 1100u - Sampler::kQueueSize);
  drain(s);
  EXPECT_EQ(axes.size() + buses.size() + events.size(), Sampler::kQueueSize);
  // Room again: sampling goes on, and the bus state reports the losses.
  axes.clear();
  buses.clear();
  s.poll(1'100'000'000);
  drain(s);
  ASSERT_EQ(buses.size(), 2u);
  EXPECT_EQ(axes.size(), 2u);
  EXPECT_EQ(buses[0].samples_dropped, 4u * 1100u - Sampler::kQueueSize);
}

TEST_F(SamplerTest, TurnaroundOfThePeriodAndLineCounters) {
  TurnaroundStats t;
  Sampler s(net_, 100.0, SamplerSources{&counters_, &t, nullptr});
  counters_.frames_in = 7;
  counters_.frames_out = 6;
  t.add(4000);
  t.add(2000);
  t.add(6000);
  s.poll(0);
  s.poll(10'000'000);  // a period without frames
  drain(s);
  ASSERT_EQ(buses.size(), 4u);
  EXPECT_EQ(buses[0].frames_in, 7u);
  EXPECT_EQ(buses[0].frames_out, 6u);
  EXPECT_EQ(buses[0].turnaround_last, 6000);
  EXPECT_EQ(buses[0].turnaround_min, 2000);
  EXPECT_EQ(buses[0].turnaround_mean, 4000);
  EXPECT_EQ(buses[0].turnaround_max, 6000);
  EXPECT_EQ(buses[1].turnaround_max, 6000);  // the same period for every slave
  EXPECT_EQ(buses[2].turnaround_max, 0);
}

TEST_F(SamplerTest, FaultRequestsGoToTheHandlerAndFaultsBecomeEvents) {
  control::FaultService faults(net_, nullptr, nullptr);
  Sampler s(net_, 100.0, SamplerSources{nullptr, nullptr, &faults.injector()});
  s.set_fault_handler([&faults](const control::ControlRequest& r, Nanos now) { return faults.handle(r, now); });
  s.poll(0);
  TelemetryRequest r = parse_telemetry_request(R"({"op":"inject","fault":{"kind":"encoder_error","slave":1}})");
  r.ticket = 42;
  ASSERT_TRUE(s.request(std::move(r)));
  s.poll(1'000'000);
  const std::optional<TelemetryReply> reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->ticket, 42u);
  ASSERT_TRUE(reply->reply.ok()) << reply->reply.error;
  EXPECT_EQ(reply->reply.id, 1);
  s.poll(10'000'000);  // the next sample notices the fault
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"clear","id":1})")));
  s.poll(11'000'000);
  ASSERT_TRUE(s.reply());
  s.poll(20'000'000);
  drain(s);
  std::vector<std::string> kinds;
  for (const EventSample& e : events) kinds.push_back(event_kind_name(e.kind));
  EXPECT_THAT(kinds, ::testing::Contains("fault_injected"));
  EXPECT_THAT(kinds, ::testing::Contains("fault_cleared"));
  for (const EventSample& e : events) {
    if (e.kind == EventKind::fault_injected) {
      EXPECT_EQ(e.slave, 1);
      EXPECT_EQ(e.value, 1u);
      EXPECT_STREQ(e.text.data(), "fault 1 encoder_error started");
    }
  }
}

// A host stall the loop recorded (runtime/host_stalls.hpp) is an event of the line at the time
// the loop ran again, with its length and threshold in us; an alarm that follows it within a
// second says so; the bus samples count the stalls.
TEST_F(SamplerTest, HostStallsAreEventsAndAnAlarmRightAfterOneSaysSo) {
  control::FaultService faults(net_, nullptr, nullptr);
  Sampler s(net_, 100.0, SamplerSources{&counters_, nullptr, &faults.injector()});
  s.poll(0);
  runtime::HostStall stall;
  stall.time = 4'000'000;
  stall.length = 12'340'000;
  stall.threshold = 2'000'000;
  stall.step_slaves = 0b11;
  stall.control_steps = 98;
  counters_.stalls.record(stall);
  const control::ControlReply injected =
      faults.handle(parse_telemetry_request(R"({"op":"inject","fault":{"kind":"alarm","slave":1,"code":"16.0"}})").fault, 5'000'000);
  ASSERT_TRUE(injected.ok()) << injected.error;
  for (Nanos t = 5'000'000; t <= 9'000'000; t += 125'000) {
    clock_.set(t);
    net_.tick(t);
  }
  s.poll(10'000'000);
  drain(s);
  const EventSample* host = nullptr;
  const EventSample* alarm = nullptr;
  for (const EventSample& e : events) {
    if (e.kind == EventKind::host_stall) host = &e;
    if (e.kind == EventKind::alarm_raised) alarm = &e;
  }
  ASSERT_NE(host, nullptr);
  EXPECT_EQ(host->time, 4'000'000);
  EXPECT_EQ(host->slave, 0);
  EXPECT_EQ(host->value, 12'340u);
  EXPECT_EQ(host->previous, 2'000u);
  EXPECT_STREQ(host->text.data(), "host stall 12.3 ms (threshold 2.0 ms): drives 1-2 caught up 98 control steps");
  EXPECT_STREQ(event_kind_name(host->kind), "host_stall");
  ASSERT_NE(alarm, nullptr);
  EXPECT_EQ(alarm->slave, 1);
  EXPECT_THAT(std::string(alarm->text.data()), ::testing::EndsWith(" after a host stall of 12.3 ms"));
  ASSERT_FALSE(buses.empty());
  EXPECT_EQ(buses.back().host_stalls, 1u);
  EXPECT_EQ(buses.back().longest_host_stall, 12'340'000);

  // One event per stall: the next sample has none; an alarm long after a stall does not mention it.
  events.clear();
  s.poll(20'000'000);
  drain(s);
  for (const EventSample& e : events) EXPECT_NE(e.kind, EventKind::host_stall);
}

TEST_F(SamplerTest, WithoutAFaultHandlerFaultRequestsAreRefused) {
  Sampler s(net_, 100.0);
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"clear_all"})")));
  s.poll(0);
  const std::optional<TelemetryReply> reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->reply.status, control::ControlReply::Status::failed);
}

TEST_F(SamplerTest, PlantSetChangesTheExternalLoadAndIsAnEvent) {
  Sampler s(net_, 100.0);
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"plant_set","slave":2,"external_load":0.5})")));
  s.poll(0);
  std::optional<TelemetryReply> reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_TRUE(reply->reply.ok()) << reply->reply.error;
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"plant_set","slave":3,"external_load":0.5})")));
  s.poll(1'000'000);
  reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->reply.status, control::ControlReply::Status::bad_request);
  EXPECT_THAT(reply->reply.error, HasSubstr("no slave 3"));
  drain(s);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, EventKind::plant_set);
  EXPECT_EQ(events[0].slave, 2);
  EXPECT_STREQ(events[0].text.data(), "external load 0.5");
}

TEST_F(SamplerTest, SamplesCarryTheStationAddressAndAPlantIsNamedByIt) {
  Sampler s(net_, 100.0);
  s.poll(0);
  ASSERT_TRUE(test::assign_station_addresses(net_, 5'000'000, 0x1001));
  s.poll(10'000'000);
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"plant_set","slave":"0x1002","external_load":0.25})")));
  s.poll(11'000'000);
  std::optional<TelemetryReply> reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_TRUE(reply->reply.ok()) << reply->reply.error;
  ASSERT_TRUE(s.request(parse_telemetry_request(R"({"op":"plant_set","slave":"0x1009","external_load":0.25})")));
  s.poll(12'000'000);
  reply = s.reply();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->reply.status, control::ControlReply::Status::bad_request);
  EXPECT_THAT(reply->reply.error, HasSubstr("no slave has station address 0x1009 (the line has 0x1001, 0x1002)"));
  drain(s);
  ASSERT_EQ(axes.size(), 4u);
  EXPECT_EQ(axes[0].station, 0) << "before the master set one";
  EXPECT_EQ(axes[2].station, 0x1001);
  EXPECT_EQ(axes[3].station, 0x1002);
  EXPECT_EQ(buses[3].station, 0x1002);
  std::vector<EventSample> plant;
  for (const EventSample& e : events)
    if (e.kind == EventKind::plant_set) plant.push_back(e);
  ASSERT_EQ(plant.size(), 1u);
  EXPECT_EQ(plant[0].slave, 2) << "the event names the position";
}

TEST(SamplerSignals, ANamedSignalThatChangesIsAnEventWithItsNameAndPoint) {
  VirtualClock clock{0};
  network::NetworkOptions o;
  o.slave_names = {"x", "y"};
  o.signals = {{"y_probe", network::SignalPoint{1, network::PlantConnection::probe1, 0, 0}, ""}};
  network::Network net(std::vector<std::string>{"a6b", "ds5c1"}, clock, o);
  Sampler s(net, 100.0);
  s.poll(0);
  net.signal(0).write(1);
  s.poll(10'000'000);
  s.poll(20'000'000);  // no change: no second event
  net.signal(0).write(0);
  s.poll(30'000'000);
  std::vector<EventSample> events;
  while (std::optional<Sample> x = s.pop())
    if (const auto* e = std::get_if<EventSample>(&*x)) events.push_back(*e);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, EventKind::signal);
  EXPECT_STREQ(event_kind_name(events[0].kind), "signal");
  EXPECT_EQ(events[0].slave, 2);
  EXPECT_EQ(events[0].value, 1u);
  EXPECT_EQ(events[0].previous, 0u);
  EXPECT_STREQ(events[0].text.data(), "y_probe (y.probe1) 0 -> 1");
  EXPECT_EQ(events[1].time, 30'000'000);
  EXPECT_STREQ(events[1].text.data(), "y_probe (y.probe1) 1 -> 0");
}

// AL state and 603Fh events compare with what the line had when the sampler started (the
// integration test telemetry_dds.sh sees them change on a real line).
TEST_F(SamplerTest, NoEventsWhileNothingChanges) {
  Sampler s(net_, 100.0);
  s.poll(0);
  s.poll(10'000'000);
  drain(s);
  EXPECT_TRUE(events.empty());
}

}  // namespace
}  // namespace vdrive::telemetry
