// vdrive run's live status line: the loop's side (LineStatusPublisher reading real ESCs of a
// Network, LineStatus carrying it across threads), the line's text (docs/cli.md "Status line"),
// and `vdrive run --status` printing it while a master's frames are answered (root: a veth pair).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/link/raw_socket_link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/line_status.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive::runtime {
namespace {

constexpr Nanos kMs = 1'000'000;

// Records what the publisher passes on: the service it wraps (the fault control in vdrive run).
class RecordingService final : public LoopService {
public:
  void poll(Nanos now) override { polls.push_back(now); }
  Nanos next_deadline() const override { return deadline; }
  std::vector<Nanos> polls;
  Nanos deadline = std::numeric_limits<Nanos>::max();
};

void firmware_sets_al_status(esc::Esc& esc, std::uint16_t status, std::uint16_t code) {
  const std::array<std::uint8_t, 2> s{static_cast<std::uint8_t>(status), static_cast<std::uint8_t>(status >> 8)};
  const std::array<std::uint8_t, 2> c{static_cast<std::uint8_t>(code), static_cast<std::uint8_t>(code >> 8)};
  esc.pdi_write(0x0134, c);
  esc.pdi_write(0x0130, s);
}

TEST(LineStatus, PublisherReadsTheEscsOfTheLine) {
  VirtualClock clock(5 * kMs);
  network::Network net(std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock);
  LineStatus status(net.size());
  LineStatusPublisher publisher(net, status, 100 * kMs);
  publisher.poll(clock.now());
  ASSERT_EQ(status.slaves(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(status.slave(i).al_status & 0x0F, 1) << "slave " << i << " powers on in Init";
    EXPECT_EQ(status.slave(i).rx_errors, 0u);
  }

  firmware_sets_al_status(net.esc(2), 0x0014, 0x001B);  // SafeOp with error: sync manager watchdog
  net.esc(1).count_rx_error(0, false);
  net.esc(1).count_rx_error(1, true);
  publisher.poll(clock.now() + 50 * kMs);  // not due yet: the old values stay
  EXPECT_EQ(status.slave(2).al_status & 0x0F, 1);
  publisher.poll(clock.now() + 100 * kMs);
  EXPECT_EQ(status.slave(2).al_status, 0x0014);
  EXPECT_EQ(status.slave(2).al_status_code, 0x001B);
  EXPECT_EQ(status.slave(1).rx_errors, 2u);
  EXPECT_EQ(publisher.next_deadline(), clock.now() + 200 * kMs);
}

// Which alarm, not only its 603Fh: A6B Err81.0, 81.1, 81.4, 81.5 and 81.6 all show FF51h
// (L32610-L32618), so the log can only name the right one from the drive's own record.
TEST(LineStatus, PublisherCarriesWhichAlarmTheDriveRaised) {
  VirtualClock clock(0);
  network::Network net(std::vector<std::string>{"a6b"}, clock);
  LineStatus status(net.size());
  LineStatusPublisher publisher(net, status, 100 * kMs);
  publisher.poll(0);
  EXPECT_EQ(status.slave(0).alarm, -1);
  ASSERT_TRUE(net.firmware(0).drive()->raise_alarm("81.1", clock.now()));
  publisher.sample();
  const SlaveStatus s = status.slave(0);
  EXPECT_EQ(s.error_code, 0xFF51);
  ASSERT_GE(s.alarm, 0);
  const auto& alarms = net.profile(0).alarms;
  ASSERT_LT(static_cast<std::size_t>(s.alarm), alarms.size());
  EXPECT_EQ(alarms[static_cast<std::size_t>(s.alarm)].code, "81.1");
  EXPECT_NE(net.profile(0).alarm_with_error_code(0xFF51)->code, "81.1") << "603Fh alone names another alarm";
}

TEST(LineStatus, PublisherPassesPollsToTheServiceItWraps) {
  VirtualClock clock(0);
  network::Network net(std::vector<std::string>{"a6b"}, clock);
  LineStatus status(net.size());
  RecordingService inner;
  LineStatusPublisher publisher(net, status, 250 * kMs, &inner);
  publisher.poll(10);
  publisher.poll(20);
  EXPECT_EQ(inner.polls, (std::vector<Nanos>{10, 20}));
  inner.deadline = 30;
  EXPECT_EQ(publisher.next_deadline(), 30);  // the earlier of the two
  inner.deadline = std::numeric_limits<Nanos>::max();
  EXPECT_EQ(publisher.next_deadline(), 10 + 250 * kMs);
}

TEST(LineStatus, PublishingOnTheLoopAllocatesNothing) {
  VirtualClock clock(0);
  network::Network net(std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock);
  LineStatus status(net.size());
  RecordingService inner;
  inner.polls.reserve(16);
  LineStatusPublisher publisher(net, status, 100 * kMs, &inner);
  const long before = vdrive::test::allocation_count();
  for (int i = 0; i < 10; ++i) {
    publisher.poll(i * 100 * kMs);  // every one due: samples all three ESCs
    (void)publisher.next_deadline();
  }
  EXPECT_EQ(vdrive::test::allocation_count() - before, 0);
  EXPECT_EQ(inner.polls.size(), 10u);
  EXPECT_EQ(status.slave(0).al_status & 0x0F, 1);
}

TEST(LineStatus, FieldsOfOneSlaveTravelTogether) {
  LineStatus status(2);
  status.publish(1, {0x0018, 0xFFFF, 0xFFFFFFFFu});
  const SlaveStatus s = status.slave(1);
  EXPECT_EQ(s.al_status, 0x0018);
  EXPECT_EQ(s.al_status_code, 0xFFFF);
  EXPECT_EQ(s.rx_errors, 0xFFFFFFFFu);
  EXPECT_EQ(s.alarm, -1);
  EXPECT_EQ(status.slave(0).al_status, 0);
  EXPECT_EQ(status.slave(0).alarm, -1) << "never published: no alarm";
  status.publish(0, {0x0008, 0, 0, 0xFF51, 17});
  EXPECT_EQ(status.slave(0).error_code, 0xFF51);
  EXPECT_EQ(status.slave(0).alarm, 17);
  EXPECT_EQ(LineStatus(kMaxStatusSlaves + 10).slaves(), kMaxStatusSlaves);
}

StatusSample sample(Nanos time, std::vector<SlaveStatus> slaves, std::uint64_t in, std::uint64_t out) {
  StatusSample s;
  s.time = time;
  s.slaves = std::move(slaves);
  s.frames_in = in;
  s.frames_out = out;
  return s;
}

TEST(StatusLineText, StatesErrorsFramesAndRate) {
  const StatusSample before = sample(0, {{0x08, 0, 0}, {0x08, 0, 0}, {0x02, 0, 0}}, 1000, 1000);
  StatusSample now = sample(500 * kMs, {{0x08, 0, 0}, {0x14, 0x001B, 3}, {0x02, 0, 1}}, 1500, 1499);
  now.dropped = 2;
  now.send_failed = 1;
  EXPECT_EQ(format_status_line(now, &before),
            "3 slaves 1:Op 2:SafeOp+E(001B) 3:PreOp | frames 1500 in 1499 out, 1000/s | rx errors 4 | dropped 2 | send failed 1");
  EXPECT_EQ(format_status_line(now, nullptr),
            "3 slaves 1:Op 2:SafeOp+E(001B) 3:PreOp | frames 1500 in 1499 out | rx errors 4 | dropped 2 | send failed 1");
}

// Part 1 of a line over processes shows a later part it could not ask as "?" (AL status 0 is
// no state an ESC reports).
TEST(StatusLineText, ASlaveNotReadIsAQuestionMark) {
  const StatusSample now = sample(0, {{0x08, 0, 0}, {0x00, 0, 0}}, 10, 10);
  EXPECT_EQ(format_status_line(now, nullptr), "2 slaves 1:Op 2:? | frames 10 in 10 out | rx errors 0 | dropped 0 | send failed 0");
}

TEST(StatusLineText, WireFaultLossesWhenServedBehindAWireStage) {
  StatusSample now = sample(0, {{0x08, 0, 0}}, 90, 88);
  now.wire = WireLosses{12, 3};
  EXPECT_EQ(format_status_line(now, nullptr),
            "1 slave 1:Op | frames 90 in 88 out | rx errors 0 | dropped 0 | send failed 0 | wire fault dropped 12 corrupted 3");
  now.wire = WireLosses{};
  EXPECT_EQ(format_status_line(now, nullptr),
            "1 slave 1:Op | frames 90 in 88 out | rx errors 0 | dropped 0 | send failed 0 | wire fault dropped 0 corrupted 0")
      << "a wire stage with nothing lost still says so";
}

TEST(StatusLineText, TheOnwardPortWhereTheLineGoesOnBeyondThisProcess) {
  StatusSample now = sample(0, {{0x08, 0, 0}}, 90, 90);
  now.onward = StatusSample::Onward{true, 90, 89};
  EXPECT_EQ(format_status_line(now, nullptr),
            "1 slave 1:Op | frames 90 in 90 out | rx errors 0 | dropped 0 | send failed 0 | onward up, 90 on, 89 back");
  now.onward->link = false;
  EXPECT_NE(format_status_line(now, nullptr).find("| onward down,"), std::string::npos);
}

TEST(StatusLineText, TakeSampleShowsTheOnwardPortOnlyWhereThereIsOne) {
  runtime::LineStatus status(1);
  runtime::LoopCounters counters;
  EXPECT_FALSE(runtime::take_sample(status, counters, 0).onward);
  counters.has_onward = true;
  counters.onward_link = true;
  counters.onward = 7;
  counters.returned = 6;
  const std::optional<StatusSample::Onward> o = runtime::take_sample(status, counters, 0).onward;
  ASSERT_TRUE(o);
  EXPECT_TRUE(o->link);
  EXPECT_EQ(o->sent, 7u);
  EXPECT_EQ(o->returned, 6u);
}

// The publisher reads the wire stage's losses with the ESCs, on the loop's thread, without
// allocating; a line without a wire stage shows none.
TEST(LineStatus, PublisherReadsTheWireStagesLosses) {
  VirtualClock clock(0);
  network::Network net(std::vector<std::string>{"a6b"}, clock);
  LineStatus status(net.size());
  LineStatusPublisher publisher(net, status, 100 * kMs);
  publisher.poll(0);
  EXPECT_FALSE(status.wire().has_value());

  fault::WireImpairment wire(1);
  fault::WireSettings lose_all;
  lose_all.drop = 1.0;
  wire.set(fault::Direction::to_slaves, lose_all);
  fault::WireSettings spoil_all;
  spoil_all.corrupt = 1.0;
  wire.set(fault::Direction::to_master, spoil_all);
  const std::vector<std::uint8_t> frame(60, 0);
  for (int i = 0; i < 3; ++i) wire.push(fault::Direction::to_slaves, frame, 0);
  for (int i = 0; i < 2; ++i) wire.push(fault::Direction::to_master, frame, 0);
  LineStatusPublisher behind_wire(net, status, 100 * kMs);
  // As vdrive run's source does (cli/run_status.cpp; served below in WireFaultDropsAreCounted...).
  behind_wire.set_wire_source([&wire] {
    WireLosses w;
    for (const fault::Direction d : {fault::Direction::to_slaves, fault::Direction::to_master}) {
      w.dropped += wire.counters(d).dropped;
      w.corrupted += wire.counters(d).corrupted;
    }
    return w;
  });
  const long before = vdrive::test::allocation_count();
  behind_wire.poll(0);
  EXPECT_EQ(vdrive::test::allocation_count() - before, 0);
  ASSERT_TRUE(status.wire().has_value());
  EXPECT_EQ(status.wire()->dropped, 3u);
  EXPECT_EQ(status.wire()->corrupted, 2u);
  const LoopCounters counters;
  const StatusSample s = take_sample(status, counters, 0);
  ASSERT_TRUE(s.wire.has_value());
  EXPECT_EQ(s.wire->dropped, 3u);
}

TEST(StatusLineText, ManySlavesAreCountedPerState) {
  std::vector<SlaveStatus> slaves(12, SlaveStatus{0x08, 0, 0});
  slaves[6] = {0x12, 0x0011, 0};
  slaves[9] = {0x04, 0, 0};
  EXPECT_EQ(format_status_line(sample(0, slaves, 7, 7), nullptr),
            "12 slaves Op 10, PreOp+E 1, SafeOp 1 (first error: 7 0011) | frames 7 in 7 out | rx errors 0 | dropped 0 | send failed 0");
}

TEST(StatusLineText, StateNames) {
  EXPECT_EQ(al_state_name(0x01), "Init");
  EXPECT_EQ(al_state_name(0x02), "PreOp");
  EXPECT_EQ(al_state_name(0x03), "Boot");
  EXPECT_EQ(al_state_name(0x04), "SafeOp");
  EXPECT_EQ(al_state_name(0x18), "Op");
  EXPECT_EQ(al_state_name(0x05), "0x5");
}

#ifdef VDRIVE_BINARY
TEST(CliStatusServe, ForcedStatusLineShowsStatesAndFrames) {
  using namespace std::chrono_literals;
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  // stderr is a pipe here: --status forces the line (one a second); warn hides the info logs.
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth.b(), "--drive", "a6b", "--drive", "ds5c1", "--status",
                                         "--no-control", "--log-level", "warn"});
  ASSERT_TRUE(run.wait_for_stderr("status: 2 slaves 1:Init 2:Init | frames 0 in 0 out", 5s)) << run.finish().err;

  link::RawSocketLink master(veth.a());
  const auto request = test::ethercat_frame(0x07 /*BRD*/, 0, 0x0000, 2);
  ASSERT_TRUE(master.send(request));
  std::array<std::uint8_t, link::kMaxFrame> buf{};
  EXPECT_EQ(master.receive(buf, 1000 * kMs), request.size());
  EXPECT_TRUE(run.wait_for_stderr("frames 1 in 1 out", 5s)) << run.finish().err;

  run.signal(SIGTERM);
  const test::ProcessResult r = run.finish();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("| rx errors 0 | dropped 0 | send failed 0"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("serving"), std::string::npos) << "--log-level warn: no info lines\n" << r.err;
}

// A wire fault injected through the control socket: the frames it drops are counted on the status
// line, and its end, when its duration runs out, is logged (issue 24 item 8).
TEST(CliStatusServe, WireFaultDropsAreCountedAndItsEndIsLogged) {
  using namespace std::chrono_literals;
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  const std::string socket = (std::filesystem::temp_directory_path() / ("vdrive-status-" + std::to_string(::getpid()) + ".sock")).string();
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth.b(), "--drive", "a6b", "--status", "--control", socket});
  ASSERT_TRUE(run.wait_for_stderr("wire fault dropped 0 corrupted 0", 5s)) << run.finish().err;

  const test::ProcessResult injected = test::run_process(
      VDRIVE_BINARY, {"fault", "inject", "--control", socket, "drop", "--probability", "1", "--duration", "1500ms"});
  ASSERT_EQ(injected.exit_code, 0) << injected.err;
  link::RawSocketLink master(veth.a());
  const auto request = test::ethercat_frame(0x07 /*BRD*/, 0, 0x0000, 2);
  std::array<std::uint8_t, link::kMaxFrame> buf{};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(master.send(request));
    EXPECT_EQ(master.receive(buf, 50 * kMs), 0u) << "frame " << i << " must be lost";
  }
  EXPECT_TRUE(run.wait_for_stderr("wire fault dropped 3 corrupted 0", 5s)) << run.finish().err;
  EXPECT_TRUE(run.wait_for_stderr("fault 1 ended: its duration ran out (drop both ways p=1 for 1500000 us)", 5s))
      << run.finish().err;
  ASSERT_TRUE(master.send(request));
  EXPECT_EQ(master.receive(buf, 1000 * kMs), request.size()) << "the wire is clean again";

  run.signal(SIGTERM);
  const test::ProcessResult r = run.finish();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("fault 1 injected: drop both ways p=1 for 1500000 us"), std::string::npos) << r.err;
  std::filesystem::remove(socket);
}

// Five A6B alarms share 603Fh FF51h (Err81.0-81.6, L32610-L32618): the log names the one the drive
// raised, not the first of the table with that 603Fh (it said Err81.0 for an Err81.1).
TEST(CliStatusServe, AnAlarmIsLoggedByItsOwnNameWhenOthersShareIts603Fh) {
  using namespace std::chrono_literals;
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  const std::string socket = (std::filesystem::temp_directory_path() / ("vdrive-alarm-" + std::to_string(::getpid()) + ".sock")).string();
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth.b(), "--drive", "a6b", "--no-status", "--control", socket});
  ASSERT_TRUE(run.wait_for_stderr("fault control on", 5s)) << run.finish().err;
  const test::ProcessResult injected =
      test::run_process(VDRIVE_BINARY, {"fault", "inject", "--control", socket, "alarm", "--slave", "1", "--code", "81.1"});
  ASSERT_EQ(injected.exit_code, 0) << injected.err;
  EXPECT_TRUE(run.wait_for_stderr("slave 1 a6b: alarm 81.1 Mailbox setting error protection (603Fh FF51h)", 5s))
      << run.finish().err;
  run.signal(SIGTERM);
  const test::ProcessResult r = run.finish();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("alarm 81.0"), std::string::npos) << r.err;
  std::filesystem::remove(socket);
}

TEST(CliStatusServe, NoStatusLineWhenStderrIsNotATerminal) {
  using namespace std::chrono_literals;
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  test::ChildProcess run(VDRIVE_BINARY, {"run", "--iface", veth.b(), "--drive", "a6b", "--no-control"});
  ASSERT_TRUE(run.wait_for_stderr("serving", 5s)) << run.finish().err;
  EXPECT_FALSE(run.wait_for_stderr("status:", 1500ms));
  run.signal(SIGTERM);
  EXPECT_EQ(run.finish().exit_code, 0);
}
#endif

}  // namespace
}  // namespace vdrive::runtime
