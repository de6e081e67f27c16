// PartRouter: part 1's control socket in front of the parts of `vdrive run --processes`. The
// parts here are real FaultServices on real networks (slaves 1-2 in part 1, slave 3 in part 2),
// each answering request lines as its socket would; faults land in the right part's injector, at
// its local position, and come back with the whole line's positions and run-wide ids. Then parts
// that are gone or hang, over real sockets: an error naming the part, within the timeout.
#include "vdrive/control/part_router.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <thread>

#include "tests/support/station_addresses.hpp"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/control/control_socket.hpp"
#include "vdrive/control/fault_service.hpp"
#include "vdrive/control/run_fault_id.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::control {
namespace {

using ::testing::HasSubstr;

TEST(RunFaultId, PartsInterleaveAndOneProcessKeepsItsIds) {
  EXPECT_EQ(run_fault_id(0, 1, 2), 1);
  EXPECT_EQ(run_fault_id(1, 1, 2), 2);
  EXPECT_EQ(run_fault_id(0, 2, 2), 3);
  EXPECT_EQ(run_fault_id(1, 2, 2), 4);
  EXPECT_EQ(run_fault_id(2, 5, 3), 15);
  EXPECT_EQ(run_fault_id(0, 0, 3), 0);  // a one-shot fault has no id
  for (int id = 1; id < 5; ++id) EXPECT_EQ(run_fault_id(0, id, 1), id);
  for (std::size_t parts = 1; parts <= 4; ++parts) {
    for (std::size_t part = 0; part < parts; ++part) {
      for (int id = 1; id <= 7; ++id) {
        const PartFaultId back = part_fault_id(run_fault_id(part, id, parts), parts);
        EXPECT_EQ(back.part, part);
        EXPECT_EQ(back.id, id);
      }
    }
  }
}

TEST(ShiftSlaveNumbers, PositionsMoveAddressesStay) {
  EXPECT_EQ(shift_slave_numbers("overload slave 1", 2), "overload slave 3");
  EXPECT_EQ(shift_slave_numbers("link_down cable at slave 1 port 1", 2), "link_down cable at slave 3 port 1");
  EXPECT_EQ(shift_slave_numbers("jam slave 2: slave 2 (ds1000a) has no drive", 10), "jam slave 12: slave 12 (ds1000a) has no drive");
  EXPECT_EQ(shift_slave_numbers("overload slave 0x1003", 2), "overload slave 0x1003");
  EXPECT_EQ(shift_slave_numbers("the network has cables into slaves 1..1", 2), "the network has cables into slaves 1..1");
  EXPECT_EQ(shift_slave_numbers("no slave here", 2), "no slave here");
  EXPECT_EQ(shift_slave_numbers("slave ", 2), "slave ");
  // A network file's name for its unnamed third slave, quoted, is a name in every part.
  EXPECT_EQ(shift_slave_numbers("'slave 3' (slave 1, ds1000a) has no object", 2), "'slave 3' (slave 3, ds1000a) has no object");
}

// Each part of a network file cut by --processes: its slaves' names and the named signals among
// them, numbered from the part's first (machine::line_part). Part 2's slave is unnamed in the file,
// so its name is the file's "slave 3".
network::NetworkOptions part_one_of_file() {
  network::NetworkOptions o;
  o.slave_names = {"x", "y"};
  o.signals = {{"mode", network::SignalPoint{0, std::nullopt, 0x6060, 0}, ""}};
  return o;
}
network::NetworkOptions part_two_of_file() {
  network::NetworkOptions o;
  o.slave_names = {"slave 3"};
  o.signals = {{"door", network::SignalPoint{0, std::nullopt, 0x6060, 0}, ""}};
  return o;
}

class PartRouterTest : public ::testing::Test {
protected:
  PartRouterTest() {
    own_.set_later_slaves(1);
    router_ = std::make_unique<PartRouter>(
        2, std::vector<RemotePart>{{2, 1, "part2.sock"}},
        [this](const ControlRequest& r) { return own_.handle(r, clock_.now()); },
        [this](const std::string& path, std::string_view line, Nanos) -> std::string {
          asked_[path].emplace_back(line);
          if (gone_) throw ControlSocketError(ControlSocketError::Kind::no_server, "cannot connect to " + path);
          ControlReply reply;
          try {
            reply = second_.handle(parse_request(line), clock_.now());
          } catch (const ProtocolError& e) {
            reply = error_reply(ControlReply::Status::bad_request, e.what());
          }
          return format_reply(reply);
        });
  }
  ControlReply ask(const std::string& line) { return parse_reply(router_->answer(line)); }

  VirtualClock clock_{1'000'000};
  network::Network line1_{std::vector<std::string>{"a6b", "ds5c1"}, clock_, part_one_of_file()};  // slaves 1-2
  network::Network line2_{std::vector<std::string>{"ds1000a"}, clock_, part_two_of_file()};       // slave 3
  FaultService own_{line1_, nullptr, nullptr};
  FaultService second_{line2_, nullptr, nullptr};
  std::map<std::string, std::vector<std::string>> asked_;
  bool gone_ = false;
  std::unique_ptr<PartRouter> router_;
};

TEST_F(PartRouterTest, AFaultForALaterSlaveActsInItsPartAtItsLocalPosition) {
  const ControlReply r = ask(R"({"op":"inject","fault":{"kind":"overload","slave":3}})");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.id, 2);  // part 2's fault 1
  ASSERT_EQ(second_.injector().active().size(), 1u);
  EXPECT_EQ(second_.injector().active()[0].spec.slave, 1);
  EXPECT_TRUE(own_.injector().active().empty());
  ASSERT_EQ(asked_["part2.sock"].size(), 1u);
  EXPECT_THAT(asked_["part2.sock"][0], HasSubstr(R"("slave":1)"));
}

TEST_F(PartRouterTest, PartOnesOwnSlavesAndTheWireStayHere) {
  const ControlReply r = ask(R"({"op":"inject","fault":{"kind":"overload","slave":2}})");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.id, 1);
  ASSERT_EQ(own_.injector().active().size(), 1u);
  EXPECT_EQ(own_.injector().active()[0].spec.slave, 2);
  EXPECT_TRUE(asked_.empty());
  // Wire faults act at part 1's port: refused here (this service has no wire stage), not forwarded.
  EXPECT_THAT(ask(R"({"op":"inject","fault":{"kind":"drop"}})").error, HasSubstr("no wire fault stage"));
  EXPECT_TRUE(asked_.empty());
  // Beyond the whole line: refused here with the line's length.
  const ControlReply beyond = ask(R"({"op":"inject","fault":{"kind":"overload","slave":4}})");
  EXPECT_EQ(beyond.status, ControlReply::Status::bad_request);
  EXPECT_THAT(beyond.error, HasSubstr("no slave 4 (the line has 3)"));
}

TEST_F(PartRouterTest, ListMergesThePartsWithRunWideIdsAndPositions) {
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":2}})").ok());
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":3}})").ok());
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"encoder_error","slave":1}})").ok());
  const ControlReply list = ask(R"({"op":"list"})");
  ASSERT_TRUE(list.ok()) << list.error;
  ASSERT_EQ(list.faults.size(), 3u);
  EXPECT_EQ(list.faults[0].id, 1);
  EXPECT_EQ(list.faults[0].description, "overload slave 2");
  EXPECT_EQ(list.faults[1].id, 3);  // part 1's fault 2
  EXPECT_EQ(list.faults[1].description, "encoder_error slave 1");
  EXPECT_EQ(list.faults[2].id, 2);  // part 2's fault 1
  EXPECT_EQ(list.faults[2].description, "overload slave 3");
}

TEST_F(PartRouterTest, ClearReachesThePartTheIdNames) {
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":2}})").ok());
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":3}})").ok());
  ASSERT_TRUE(ask(R"({"op":"clear","id":2})").ok());
  EXPECT_TRUE(second_.injector().active().empty());
  EXPECT_EQ(own_.injector().active().size(), 1u);
  const ControlReply again = ask(R"({"op":"clear","id":2})");
  EXPECT_EQ(again.status, ControlReply::Status::bad_request);
  EXPECT_EQ(again.error, "no active fault 2");
  EXPECT_EQ(ask(R"({"op":"clear","id":5})").error, "no active fault 5");  // part 1's fault 3: none
  ASSERT_TRUE(ask(R"({"op":"clear","id":1})").ok());
  EXPECT_TRUE(own_.injector().active().empty());
}

TEST_F(PartRouterTest, ClearAllClearsEveryPart) {
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":1}})").ok());
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":3}})").ok());
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"over_voltage","slave":3}})").ok());
  const ControlReply r = ask(R"({"op":"clear_all"})");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.cleared, 3);
  EXPECT_TRUE(own_.injector().active().empty());
  EXPECT_TRUE(second_.injector().active().empty());
}

TEST_F(PartRouterTest, AStationAddressGoesToThePartThatHasIt) {
  clock_.advance(100'000);
  ASSERT_TRUE(test::assign_station_addresses(line1_, clock_.now(), 0x1001));
  ASSERT_TRUE(test::assign_station_addresses(line2_, clock_.now(), 0x1003));
  const ControlReply r = ask(R"({"op":"inject","fault":{"kind":"overload","slave":"0x1003"}})");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.id, 2);
  ASSERT_EQ(second_.injector().active().size(), 1u);
  EXPECT_EQ(second_.injector().active()[0].spec.slave, 1);
  EXPECT_EQ(ask(R"({"op":"list"})").faults.at(0).description, "overload slave 3");

  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":"0x1002"}})").ok());
  EXPECT_EQ(own_.injector().active().size(), 1u);
  const ControlReply where = ask(R"({"op":"find_station","station":"0x1003"})");
  ASSERT_TRUE(where.ok()) << where.error;
  EXPECT_EQ(where.slave, 3);

  const ControlReply none = ask(R"({"op":"inject","fault":{"kind":"overload","slave":"0x1009"}})");
  EXPECT_EQ(none.status, ControlReply::Status::bad_request);
  EXPECT_THAT(none.error, HasSubstr("overload slave 0x1009: no part of this run's line has station address 0x1009"));
  EXPECT_THAT(none.error, HasSubstr("part 1 (slaves 1-2): no slave has station address 0x1009 (it has 0x1001, 0x1002)"));
  EXPECT_THAT(none.error, HasSubstr("part 2 (slave 3): no slave has station address 0x1009 (it has 0x1003)"));
}

TEST_F(PartRouterTest, APartThatHasEndedIsNamedAndTheOthersStillReport) {
  ASSERT_TRUE(ask(R"({"op":"inject","fault":{"kind":"overload","slave":2}})").ok());
  gone_ = true;
  const ControlReply inject = ask(R"({"op":"inject","fault":{"kind":"overload","slave":3}})");
  EXPECT_EQ(inject.status, ControlReply::Status::failed);
  EXPECT_THAT(inject.error, HasSubstr("part 2 (slave 3) does not answer"));
  const ControlReply list = ask(R"({"op":"list"})");
  EXPECT_EQ(list.status, ControlReply::Status::failed);
  EXPECT_THAT(list.error, HasSubstr("part 2 (slave 3) does not answer"));
  EXPECT_THAT(list.error, HasSubstr("the other parts' active faults: 1 overload slave 2"));
  const ControlReply clear = ask(R"({"op":"clear_all"})");
  EXPECT_EQ(clear.status, ControlReply::Status::failed);
  EXPECT_THAT(clear.error, HasSubstr("1 fault(s) cleared in the other parts"));
  EXPECT_TRUE(own_.injector().active().empty());
}

// The status line of part 1 counts every part's slaves: line_status is each slave's AL state, in
// line order, and a part that does not answer is the error.
TEST_F(PartRouterTest, LineStatusListsEverySlaveOfEveryPartInLineOrder) {
  ControlReply r = ask(R"({"op":"line_status"})");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.states.size(), 3u);
  for (const SlaveState& s : r.states) EXPECT_EQ(s.al_status & 0x0F, 1) << "every slave in Init";
  EXPECT_EQ(asked_["part2.sock"].back(), R"({"op":"line_status"})");
  gone_ = true;
  r = ask(R"({"op":"line_status"})");
  EXPECT_EQ(r.status, ControlReply::Status::failed);
  EXPECT_THAT(r.error, HasSubstr("part 2 (slave 3) does not answer"));
}

std::int64_t read(network::Network& net, const std::string& point) { return net.resolve(net.parse_point(point)).read(); }

TEST_F(PartRouterTest, SignalsListEveryPartsNamedSignalsInLineOrder) {
  const ControlReply r = ask(R"({"op":"signals"})");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.signals.size(), 2u);
  EXPECT_EQ(r.signals[0].name, "mode");
  EXPECT_EQ(r.signals[0].point, "x 0x6060:0");
  EXPECT_EQ(r.signals[1].name, "door");
  EXPECT_EQ(r.signals[1].point, "slave 3 0x6060:0") << "a name, not a position to shift";
  EXPECT_EQ(r.signals[1].type, "I8");
  ASSERT_EQ(asked_["part2.sock"].size(), 1u);
}

TEST_F(PartRouterTest, ANamedSignalOfALaterPartIsFoundThere) {
  const ControlReply set = ask(R"({"op":"signal_set","signal":"door","value":8})");
  ASSERT_TRUE(set.ok()) << set.error;
  ASSERT_EQ(set.signals.size(), 1u);
  EXPECT_EQ(set.signals[0].name, "door");
  EXPECT_EQ(set.signals[0].value, 8);
  EXPECT_EQ(read(line2_, "1 0x6060:0"), 8);
  EXPECT_EQ(read(line1_, "1 0x6060:0"), 0) << "part 1's own entry is untouched";
  // A point at a named slave is asked the same way; part 1's own are answered there.
  const ControlReply by_slave_name = ask(R"({"op":"signal_get","signal":"slave 3 0x6060:0"})");
  ASSERT_TRUE(by_slave_name.ok()) << by_slave_name.error;
  EXPECT_EQ(by_slave_name.signals.at(0).value, 8);
  asked_.clear();
  ASSERT_TRUE(ask(R"({"op":"signal_set","signal":"mode","value":-2})").ok());
  EXPECT_EQ(read(line1_, "1 0x6060:0"), -2);
  EXPECT_TRUE(asked_.empty());
  // The part that has the signal refuses the value: that refusal, not "no part has it".
  const ControlReply too_big = ask(R"({"op":"signal_set","signal":"door","value":300})");
  EXPECT_EQ(too_big.status, ControlReply::Status::bad_request);
  EXPECT_THAT(too_big.error, HasSubstr("signal 'door': 300 is outside"));
}

TEST_F(PartRouterTest, ASignalNoPartHasIsOneErrorSayingWhatEachHas) {
  const ControlReply none = ask(R"({"op":"signal_get","signal":"window"})");
  EXPECT_EQ(none.status, ControlReply::Status::bad_request);
  EXPECT_EQ(none.error, "no part of this run's line has signal 'window' (part 1 (slaves 1-2) has mode; part 2 (slave 3) "
                        "has door) and not a point: 'window': expected SLAVE INDEX:SUBINDEX (e.g. 'do 0x7000:1') or "
                        "SLAVE.CONNECTION (e.g. 'x.home')");
  const ControlReply no_slave = ask(R"({"op":"signal_get","signal":"z.home"})");
  EXPECT_EQ(no_slave.status, ControlReply::Status::bad_request);
  EXPECT_EQ(no_slave.error, "'z.home': no part of this run's line has a slave 'z' (name one of the network file's "
                            "slaves, or give a position 1-3)");
  // A slave part 1 has, with an entry it lacks: part 1's answer, the other parts are not asked.
  asked_.clear();
  EXPECT_THAT(ask(R"({"op":"signal_get","signal":"y 0x7000:1"})").error, HasSubstr("'y' (slave 2, ds5c1) has no object 7000h:01h"));
  EXPECT_TRUE(asked_.empty());
}

TEST_F(PartRouterTest, APointAtALaterPositionGoesToItsPartAtItsLocalPosition) {
  const ControlReply set = ask(R"({"op":"signal_set","signal":"3 0x6060:0","value":6})");
  ASSERT_TRUE(set.ok()) << set.error;
  ASSERT_EQ(asked_["part2.sock"].size(), 1u);
  EXPECT_THAT(asked_["part2.sock"][0], HasSubstr(R"("signal":"1 0x6060:0")"));
  EXPECT_EQ(read(line2_, "1 0x6060:0"), 6);
  ASSERT_EQ(set.signals.size(), 1u);
  EXPECT_EQ(set.signals[0].name, "3 0x6060:0") << "as the user asked for it";
  EXPECT_EQ(set.signals[0].point, "slave 3 0x6060:0");
  EXPECT_EQ(set.signals[0].value, 6);
  EXPECT_THAT(ask(R"({"op":"signal_get","signal":"3 0x7000:1"})").error,
              HasSubstr("'slave 3' (slave 3, ds1000a) has no object 7000h:01h"));
  // Part 1's positions stay here; beyond the line is refused with the line's length.
  asked_.clear();
  ASSERT_TRUE(ask(R"({"op":"signal_get","signal":"2 0x6060:0"})").ok());
  EXPECT_TRUE(asked_.empty());
  const ControlReply beyond = ask(R"({"op":"signal_get","signal":"4.home"})");
  EXPECT_EQ(beyond.status, ControlReply::Status::bad_request);
  EXPECT_EQ(beyond.error, "'4.home': no slave 4 (this run's line has slaves 1-3)");
}

TEST_F(PartRouterTest, SignalsOfAPartThatDoesNotAnswer) {
  gone_ = true;
  const ControlReply list = ask(R"({"op":"signals"})");
  EXPECT_EQ(list.status, ControlReply::Status::failed);
  EXPECT_THAT(list.error, HasSubstr("part 2 (slave 3) does not answer"));
  EXPECT_THAT(list.error, HasSubstr("the other parts' signals: mode (x 0x6060:0) = 0"));
  const ControlReply named = ask(R"({"op":"signal_get","signal":"door"})");
  EXPECT_EQ(named.status, ControlReply::Status::failed);
  EXPECT_THAT(named.error, HasSubstr("no part of this run's line has signal 'door' (part 1 (slaves 1-2) has mode)"));
  EXPECT_THAT(named.error, HasSubstr("part 2 (slave 3) does not answer"));
  const ControlReply point = ask(R"({"op":"signal_get","signal":"3 0x6060:0"})");
  EXPECT_EQ(point.status, ControlReply::Status::failed);
  EXPECT_THAT(point.error, HasSubstr("part 2 (slave 3) does not answer"));
  // Part 1's own signals still work.
  EXPECT_TRUE(ask(R"({"op":"signal_get","signal":"mode"})").ok());
}

// `--processes` without a network file: no slave names, so a later part's points carry its own
// positions, which come back as the whole line's.
TEST(PartRouterPlainLineTest, PointsComeBackAtTheWholeLinesPositions) {
  VirtualClock clock{1'000'000};
  network::Network one{std::vector<std::string>{"a6b", "ds5c1"}, clock};
  network::Network two{std::vector<std::string>{"ds1000a"}, clock};
  FaultService own(one, nullptr, nullptr), second(two, nullptr, nullptr);
  PartRouter router(
      2, {{2, 1, "part2.sock"}}, [&](const ControlRequest& r) { return own.handle(r, clock.now()); },
      [&](const std::string&, std::string_view line, Nanos) { return format_reply(second.handle(parse_request(line), clock.now())); });
  const ControlReply get = parse_reply(router.answer(R"({"op":"signal_get","signal":"3 0x6060:0"})"));
  ASSERT_TRUE(get.ok()) << get.error;
  EXPECT_EQ(get.signals.at(0).name, "3 0x6060:0");
  EXPECT_EQ(get.signals.at(0).point, "3 0x6060:0");
  const ControlReply too_big = parse_reply(router.answer(R"({"op":"signal_set","signal":"3 0x6060:0","value":300})"));
  EXPECT_EQ(too_big.status, ControlReply::Status::bad_request);
  EXPECT_THAT(too_big.error, HasSubstr("signal '3 0x6060:0': 300 is outside")) << "the user's point, not part 2's '1 0x6060:0'";
  EXPECT_THAT(parse_reply(router.answer(R"({"op":"signal_get","signal":"3 0x7000:1"})")).error,
              HasSubstr("slave 3 (ds1000a) has no object 7000h:01h"));
  const ControlReply list = parse_reply(router.answer(R"({"op":"signals"})"));
  ASSERT_TRUE(list.ok()) << list.error;
  EXPECT_TRUE(list.signals.empty());
}

// Over real sockets: a part whose socket is gone, and one that accepts but never answers.
class PartRouterSocketTest : public ::testing::Test {
protected:
  void SetUp() override {
    char tmpl[] = "/tmp/vdrive-router-test-XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    base_ = tmpl;
  }
  void TearDown() override { std::filesystem::remove_all(base_); }

  std::string base_;
};

TEST_F(PartRouterSocketTest, AGoneOrHungPartIsAnErrorWithinTheTimeout) {
  const std::string hung = base_ + "/part2.sock";
  const std::string gone = base_ + "/part3.sock";
  ControlServer server(
      hung, [](std::string_view) { std::this_thread::sleep_for(std::chrono::milliseconds(1500)); return std::string("{}"); },
      [](unsigned) { return std::string("denied"); });
  PartRouter router(
      1, {{1, 1, hung}, {2, 2, gone}},
      [](const ControlRequest&) { return ControlReply{}; },
      [](const std::string& path, std::string_view line, Nanos timeout) { return control_call(path, line, timeout); },
      200'000'000);
  const auto start = std::chrono::steady_clock::now();
  const ControlReply to_hung = parse_reply(router.answer(R"({"op":"inject","fault":{"kind":"overload","slave":2}})"));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(1000));
  EXPECT_EQ(to_hung.status, ControlReply::Status::failed);
  EXPECT_THAT(to_hung.error, HasSubstr("part 2 (slave 2) does not answer"));
  const ControlReply to_gone = parse_reply(router.answer(R"({"op":"clear","id":3})"));  // part 3's fault 1
  EXPECT_EQ(to_gone.status, ControlReply::Status::failed);
  EXPECT_THAT(to_gone.error, HasSubstr("part 3 (slaves 3-4) does not answer"));
  EXPECT_THAT(to_gone.error, HasSubstr(gone));
}

}  // namespace
}  // namespace vdrive::control
