// A drive that faults in the middle of the csp sine, as a user's fault button makes it: the sine
// program resets the fault once the cause is gone, enables the drive again and moves on from where
// the axis stands, with no step in 607Ah and no further alarm (a jump of the command is what the
// A6B answers with Err27.4, position command error).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "master/cia402_program.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::master {
namespace {

std::int32_t object32(network::Network& n, std::size_t slave, std::uint16_t index) {
  od::ObjectStore& o = n.firmware(slave).objects();
  const auto bytes = o.raw(*o.dictionary().find(index, 0));
  std::int32_t v = 0;
  for (std::size_t i = 0; i < bytes.size() && i < 4; ++i) v |= static_cast<std::int32_t>(bytes[i]) << (8 * i);
  return v;
}

TEST(SineRecovery, AFaultedDriveIsEnabledAgainAndMovesOnWithoutAStep) {
  test::VirtualLine line({"a6b", "ds5c1"});
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 2u);
  master.set_mailbox_timeout(20'000'000);
  SineProgramOptions sine;
  sine.cycle = 1'000'000;
  sine.frequency_hz = 0.5;
  sine.revolutions = 0.25;
  sine.motion = 60'000'000'000;
  SineProgram program(sine);
  OpRunOptions o;
  o.cycle = 1'000'000;
  o.drift_frames = 200;
  o.mailbox_timeout = 20'000'000;
  o.recover = true;
  program.attach(o);
  o.cycles = 14000;  // Err16.0 can be reset 10 s after it occurs (L32918)
  fault::FaultInjector faults(line.network(), nullptr);
  int cycle = 0, fault_id = 0;
  std::int32_t last_target = 0;
  std::int64_t max_step_after = 0, max_following_after = 0, max_gap_after = 0;
  std::set<std::uint16_t> alarms;
  bool enabled_again = false;
  o.done = [&] {
    ++cycle;
    const Nanos now = line.clock().now();
    if (cycle == 1500) {
      fault::FaultSpec overload;
      overload.kind = fault::FaultKind::overload;
      overload.slave = 1;
      fault_id = faults.inject(overload, now);
    }
    if (cycle == 1800) faults.clear(fault_id, now);
    const auto error = static_cast<std::uint16_t>(object32(line.network(), 0, 0x603F) & 0xFFFF);
    if (error != 0) alarms.insert(error);
    const std::int32_t target = object32(line.network(), 0, 0x607A);
    if (cycle > 1800) {
      max_step_after = std::max<std::int64_t>(max_step_after, std::llabs(static_cast<std::int64_t>(target) - last_target));
      if ((object32(line.network(), 0, 0x6041) & 0x6F) == 0x27) enabled_again = true;
      if (enabled_again)
        max_following_after = std::max<std::int64_t>(max_following_after, std::llabs(object32(line.network(), 0, 0x60F4)));
      if (enabled_again)
        max_gap_after = std::max<std::int64_t>(max_gap_after, std::llabs(static_cast<std::int64_t>(target) - object32(line.network(), 0, 0x6064)));
    }
    last_target = target;
    return false;
  };
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_EQ(alarms, (std::set<std::uint16_t>{0xFF10})) << "only the overload, nothing after the re-enable";
  EXPECT_TRUE(enabled_again);
  const DriveResult& a6b = program.results()[0];
  // A quarter revolution at 0.5 Hz moves at most amplitude * 2 pi f per second: per 1 ms cycle,
  // about 0.003 * amplitude; a step would be of the order of the amplitude.
  EXPECT_LT(max_step_after, static_cast<std::int64_t>(a6b.amplitude * 0.01)) << "607Ah jumped after the re-enable";
  EXPECT_EQ(a6b.statusword & 0x006F, 0x0027) << describe(a6b);
  EXPECT_LE(max_following_after, a6b.following_window) << "following error after the re-enable";
  EXPECT_LE(max_gap_after, a6b.following_window) << "607Ah - 6064h after the re-enable";
}

// The same fault with the program recovering (vdrive-master op --recover): the outage is counted
// with its 603Fh code and its length, reported as it starts and ends, and the verdict is that the
// drive came back, not that it faulted.
TEST(SineRecovery, RecoveringTheOutageIsCountedWithItsCodeAndTheVerdictIsOk) {
  test::VirtualLine line({"a6b", "ds5c1"});
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 2u);
  master.set_mailbox_timeout(20'000'000);
  SineProgramOptions sine;
  sine.frequency_hz = 0.5;
  sine.revolutions = 0.25;
  sine.motion = 60'000'000'000;
  sine.recover = true;
  sine.recovery_bound = 12'000'000'000;  // Err16.0 can be reset 10 s after it occurs
  SineProgram program(sine);
  std::vector<DriveRecovery::Event> events;
  program.on_recovery([&](const DriveResult& r, DriveRecovery::Event e) {
    EXPECT_EQ(r.station, program.results()[0].station) << "only the overloaded drive";
    events.push_back(e);
  });
  OpRunOptions o;
  o.drift_frames = 200;
  o.mailbox_timeout = 20'000'000;
  o.recover = true;
  program.attach(o);
  o.cycles = 14000;
  fault::FaultInjector faults(line.network(), nullptr);
  int cycle = 0, fault_id = 0;
  o.done = [&] {
    ++cycle;
    fault::FaultSpec overload;
    overload.kind = fault::FaultKind::overload;
    overload.slave = 1;
    if (cycle == 1500) fault_id = faults.inject(overload, line.clock().now());
    if (cycle == 1800) faults.clear(fault_id, line.clock().now());
    return false;
  };
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_TRUE(r.recovered());
  const DriveResult& a6b = program.results()[0];
  EXPECT_EQ(events, (std::vector<DriveRecovery::Event>{DriveRecovery::Event::lost, DriveRecovery::Event::recovered}));
  EXPECT_EQ(a6b.recovery.outages(), 1u);
  EXPECT_EQ(a6b.recovery.recoveries(), 1u);
  ASSERT_EQ(a6b.recovery.codes().size(), 1u);
  EXPECT_EQ(a6b.recovery.codes()[0].code, 0xFF10);
  // Not before the 10 s the A6B holds Err16.0, and not much later: the reset follows at once.
  EXPECT_GE(a6b.recovery.longest(), 9'000'000'000);
  EXPECT_LE(a6b.recovery.longest(), 11'000'000'000);
  EXPECT_TRUE(a6b.ok()) << describe(a6b);
  EXPECT_NE(describe(a6b).find("1 outages, 1 recovered (603Fh FF10h x1)"), std::string::npos) << describe(a6b);
  EXPECT_EQ(program.results()[1].recovery.outages(), 0u);
  EXPECT_TRUE(program.results()[1].ok()) << describe(program.results()[1]);
}

// A drive kept in Fault (the overload never cleared) past the bound did not come back: the
// verdict fails and says so.
TEST(SineRecovery, ADriveNotBackWithinTheBoundFails) {
  test::VirtualLine line({"a6b"});
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 1u);
  master.set_mailbox_timeout(20'000'000);
  SineProgramOptions sine;
  sine.frequency_hz = 0.5;
  sine.revolutions = 0.25;
  sine.motion = 60'000'000'000;
  sine.recover = true;
  sine.recovery_bound = 2'000'000'000;
  SineProgram program(sine);
  std::size_t overdue_events = 0;
  program.on_recovery([&](const DriveResult&, DriveRecovery::Event e) { overdue_events += e == DriveRecovery::Event::overdue; });
  OpRunOptions o;
  o.drift_frames = 200;
  o.mailbox_timeout = 20'000'000;
  o.recover = true;
  program.attach(o);
  o.cycles = 5000;
  fault::FaultInjector faults(line.network(), nullptr);
  int cycle = 0;
  o.done = [&] {
    if (++cycle == 1500) {
      fault::FaultSpec overload;
      overload.kind = fault::FaultKind::overload;
      overload.slave = 1;
      faults.inject(overload, line.clock().now());
    }
    return false;
  };
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error;
  const DriveResult& a6b = program.results()[0];
  EXPECT_EQ(overdue_events, 1u);
  EXPECT_EQ(a6b.recovery.overdue(), 1u);
  EXPECT_TRUE(a6b.recovery.out());
  EXPECT_FALSE(a6b.ok());
  EXPECT_NE(describe(a6b).find("FAILED (not enabled again within the bound: 1 of 1 outages)"), std::string::npos)
      << describe(a6b);
}

}  // namespace
}  // namespace vdrive::master
