// Host stalls (vdrive/runtime/host_stalls.hpp): the real-time loop round (serve_once) names a
// lateness beyond max(floor, 2 bus cycles) as a stall, with what the drives saw, without
// allocating; ordinary lateness and virtual time are no stall; a loop thread that is really kept
// from running (a service that sleeps 20 ms) is reported, in the record and the status line; the
// record ring keeps the last kLog stalls whole.
#include "vdrive/runtime/host_stalls.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/dc_sine_line.hpp"
#include "vdrive/link/loopback_link.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/runtime/line_status.hpp"

namespace vdrive::runtime {
namespace {

using ::testing::HasSubstr;

constexpr Nanos kMs = 1'000'000;

// Three drives in Op with DC at 1 ms, following a sine; then served by the real-time round on the
// virtual clock, so the test decides how late the loop gets back.
class StallInOp : public ::testing::Test {
protected:
  void SetUp() override {
    master::Master m{line_, line_.clock()};
    ASSERT_EQ(m.scan(), 3u);
    dc_.op.cycles = 300;
    const master::OpRunResult r = master::run_to_op(m, dc_.op);
    ASSERT_TRUE(r.ok()) << r.error;
  }
  // One loop round at the clock's time, waiting for nothing.
  void round() { serve_once(line_.network(), *ends_.second, clock(), clock().now(), counters_); }
  // One round on time, then the next `late` after the deadline it planned.
  void late_round(Nanos late) {
    round();
    clock().set(line_.network().next_deadline() + late);
    round();
  }
  VirtualClock& clock() { return line_.clock(); }

  master::test::VirtualLine line_{{"a6b", "ds5c1", "ds1000a"}};
  test::DcSineLine dc_{kMs};
  std::pair<std::unique_ptr<link::LoopbackLink>, std::unique_ptr<link::LoopbackLink>> ends_ = link::make_loopback_pair();
  LoopCounters counters_;
};

TEST_F(StallInOp, LatenessUnderTwoBusCyclesIsNoStall) {
  late_round(kMs / 2);
  late_round(3 * kMs / 2);  // beyond the 1 ms floor, but the threshold is 2 cycles of 1 ms
  EXPECT_EQ(counters_.stalls.count(), 0u);
  EXPECT_FALSE(counters_.stalls.latest());
}

TEST_F(StallInOp, AStallIsNamedWithWhatTheDrivesSawWithoutAllocating) {
  round();
  const Nanos resume = line_.network().next_deadline() + 12 * kMs;
  clock().set(resume);
  const long before = vdrive::test::allocation_count();
  round();
  EXPECT_EQ(vdrive::test::allocation_count() - before, 0) << "the loop thread allocated while it recorded a stall";

  ASSERT_EQ(counters_.stalls.count(), 1u);
  const std::optional<HostStall> s = counters_.stalls.latest();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->number, 1u);
  EXPECT_EQ(s->time, resume);
  EXPECT_EQ(s->length, 12 * kMs);
  EXPECT_EQ(s->cycle, kMs) << "the drives' SYNC0 cycle";
  EXPECT_EQ(s->threshold, 2 * kMs) << "max(1 ms, 2 cycles)";
  EXPECT_EQ(s->sync0_slaves, 0b111u) << "every drive runs on SYNC0";
  // SYNC0 was due at most one cycle before the planned deadline: 12 or 13 pulses fell in the stall.
  EXPECT_GE(s->sync0_pulses, 12u);
  EXPECT_LE(s->sync0_pulses, 13u);
  EXPECT_EQ(s->step_slaves, 0b111u);
  EXPECT_GE(s->control_steps, 12u);
  EXPECT_EQ(counters_.stalls.longest(), 12 * kMs);

  const std::string text = describe(*s);
  EXPECT_THAT(text, HasSubstr("host stall 12.0 ms (threshold 2.0 ms): slaves 1-3 missed 1"));
  EXPECT_THAT(text, HasSubstr("SYNC0 pulses and caught up"));
  EXPECT_THAT(text, HasSubstr("control steps"));

  // Back on time: no second stall; virtual time never stalls, however far it jumps.
  round();
  clock().set(clock().now() + 200 * kMs);
  run_until(line_.network(), *ends_.second, clock(), clock().now() + 100 * kMs, counters_);
  EXPECT_EQ(counters_.stalls.count(), 1u);

  // A fault seen within a second after it follows it; later ones do not.
  EXPECT_EQ(after_stall(counters_.stalls.just_before(resume + 500 * kMs)), " after a host stall of 12.0 ms");
  EXPECT_FALSE(counters_.stalls.just_before(resume + kStallAftermath + 1));
  EXPECT_FALSE(counters_.stalls.just_before(resume - 1));
}

TEST_F(StallInOp, TheFloorIsConfigurable) {
  counters_.stalls.set_floor(20 * kMs);
  late_round(12 * kMs);
  EXPECT_EQ(counters_.stalls.count(), 0u);
  counters_.stalls.set_floor(kMs);
  late_round(12 * kMs);
  EXPECT_EQ(counters_.stalls.count(), 1u);
}

// The loop thread really kept from running: a service that sleeps 20 ms once, on a line served by
// serve() in real time. The drive's control steps (every control period, in Init too) are late.
class SleepOnce final : public LoopService {
public:
  void poll(Nanos) override {
    if (++polls_ == 200) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (polls_ > 200) slept_.store(true);
  }
  Nanos next_deadline() const override { return INT64_MAX; }
  bool slept() const { return slept_.load(); }

private:
  int polls_ = 0;
  std::atomic<bool> slept_{false};
};

TEST(HostStallRealTime, ALoopThreadThatDoesNotRunIsReportedAsAStall) {
  MonotonicClock clock;
  network::Network net(std::vector<std::string>{"a6b"}, clock);
  auto ends = link::make_loopback_pair();
  link::Link* line = ends.second.get();
  LineStatus status(net.size());
  LoopCounters counters;
  // A host busy with other work keeps an unprivileged thread waiting for a scheduler tick (4 ms
  // here) now and then: those are stalls too, but this test looks for its own.
  counters.stalls.set_floor(10 * kMs);
  SleepOnce sleeper;
  LineStatusPublisher publisher(net, status, 10 * kMs, &sleeper);
  std::atomic<bool> stop{false};
  std::thread loop([&] { serve(net, *line, clock, stop, counters, &publisher); });
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!sleeper.slept() && std::chrono::steady_clock::now() < give_up) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  stop = true;
  loop.join();
  ASSERT_TRUE(sleeper.slept());

  // The host may have stalled the loop on its own too; the 20 ms one is among them.
  EXPECT_GE(counters.stalls.longest(), 15 * kMs);
  ASSERT_GE(counters.stalls.count(), 1u);
  std::optional<HostStall> found;
  for (std::uint64_t k = 1; k <= counters.stalls.count(); ++k)
    if (const auto s = counters.stalls.get(k); s && s->length >= 15 * kMs) found = s;
  std::string seen;
  for (std::uint64_t k = 1; k <= counters.stalls.count(); ++k)
    if (const auto s = counters.stalls.get(k)) seen += describe(*s) + "\n";
  ASSERT_TRUE(found) << "no stall of about 20 ms among " << counters.stalls.count() << ":\n" << seen;
  EXPECT_LT(found->length, 500 * kMs);
  EXPECT_EQ(found->threshold, 10 * kMs) << "in Init no bus cycle: the floor";
  EXPECT_EQ(found->step_slaves, 1u) << "the drive's control step was late";
  EXPECT_GT(found->control_steps, 15u);
  EXPECT_THAT(describe(*found), HasSubstr("drive 1 caught up"));
  EXPECT_GE(counters.stalls.longest(), found->length);

  // The status line counts it.
  const StatusSample sample = take_sample(status, counters, 0);
  EXPECT_EQ(sample.host_stalls, counters.stalls.count());
  EXPECT_THAT(format_status_line(sample, nullptr), HasSubstr(" | host stalls " + std::to_string(sample.host_stalls) + ", longest "));
}

TEST(HostStallRecords, TheRingKeepsTheLastOnesWholeAndTheCounterAll) {
  HostStalls stalls;
  EXPECT_EQ(stalls.count(), 0u);
  EXPECT_FALSE(stalls.get(0));
  EXPECT_FALSE(stalls.get(1));
  for (int k = 1; k <= 20; ++k) {
    HostStall s;
    s.time = k * 100 * kMs;
    s.length = (k == 7 ? 50 : k) * kMs;
    s.threshold = kMs;
    stalls.record(s);
  }
  EXPECT_EQ(stalls.count(), 20u);
  EXPECT_EQ(stalls.longest(), 50 * kMs);
  EXPECT_FALSE(stalls.get(4)) << "overwritten: the ring holds the last 16";
  ASSERT_TRUE(stalls.get(5));
  EXPECT_EQ(stalls.get(5)->length, 5 * kMs);
  EXPECT_EQ(stalls.get(20)->time, 2000 * kMs);
  EXPECT_FALSE(stalls.get(21));
  EXPECT_EQ(describe(*stalls.get(20)), "host stall 20.0 ms (threshold 1.0 ms): the line's timers ran late");
  EXPECT_EQ(after_stall(std::nullopt), "");
}

// What the CI run of 2026-11-27 saw: an 80 ms stall, then short ones while the host was still busy,
// recorded after the loop sampled the alarm a reader names. The fault follows the long one.
TEST(HostStallRecords, AFaultFollowsTheLongestStallBeforeItNotOneRecordedAfter) {
  HostStalls stalls;
  const auto add = [&](Nanos time, Nanos length) {
    HostStall s;
    s.time = time;
    s.length = length;
    s.threshold = kMs;
    stalls.record(s);
  };
  add(1000 * kMs, 2 * kMs);
  add(5000 * kMs, 80 * kMs);
  add(5000 * kMs + 100'000, 3 * kMs);
  add(5100 * kMs, 2 * kMs);  // after the sample below
  const Nanos sampled = 5050 * kMs;
  EXPECT_EQ(after_stall(stalls.just_before(sampled)), " after a host stall of 80.0 ms");
  EXPECT_EQ(after_stall(stalls.just_before(5000 * kMs)), " after a host stall of 80.0 ms") << "at the same instant";
  EXPECT_EQ(after_stall(stalls.just_before(5950 * kMs)), " after a host stall of 80.0 ms");
  EXPECT_EQ(after_stall(stalls.just_before(6050 * kMs)), " after a host stall of 2.0 ms") << "only the last is within a second";
  EXPECT_FALSE(stalls.just_before(7000 * kMs));
  EXPECT_EQ(after_stall(stalls.just_before(1500 * kMs)), " after a host stall of 2.0 ms");
  EXPECT_FALSE(stalls.just_before(999 * kMs)) << "before every stall";
}

TEST(HostStallRecords, TheDescriptionFitsAFixedBufferAndListsSlavesAsRanges) {
  HostStall s;
  s.length = 3'460'000;
  s.threshold = 2 * kMs;
  s.sync0_slaves = 0b1011;  // 1, 2, 4
  s.sync0_pulses = 4;
  s.step_slaves = 0b1000'0000'0000'0001;  // 1, 16
  s.control_steps = 1;
  EXPECT_EQ(describe(s), "host stall 3.5 ms (threshold 2.0 ms): slaves 1-2,4 missed 3 SYNC0 pulses, drives 1,16 caught up 1 "
                         "control step");
  std::array<char, 20> small{};
  EXPECT_EQ(describe(s, small), 19u);
  EXPECT_STREQ(small.data(), "host stall 3.5 ms (");
}

// A later part of `vdrive run --processes` names its slaves by their place in the whole line.
TEST(HostStallRecords, ALaterPartNamesItsSlavesByWholeLinePosition) {
  HostStall s;
  s.length = 3 * kMs;
  s.threshold = 2 * kMs;
  s.sync0_slaves = 0b11;  // its own slaves 1 and 2
  s.sync0_pulses = 2;
  s.step_slaves = 0b11;
  s.control_steps = 24;
  EXPECT_EQ(describe(s, 2), "host stall 3.0 ms (threshold 2.0 ms): slaves 3-4 missed 1 SYNC0 pulse and caught up 24 control steps");
  std::array<char, 128> buf{};
  describe(s, buf, 2);
  EXPECT_STREQ(buf.data(), describe(s, 2).c_str());
}

}  // namespace
}  // namespace vdrive::runtime
