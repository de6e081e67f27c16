// Batched control steps (Network::set_control_step_batch): the loop need not wake for each drive's
// control step; the steps wait up to the batch for an interrupt or a loop round and then run, each
// at its own instant, the drives one step each in turn. A master sees exactly the process data it
// sees with steps on time; every interrupt catches the drive up before the firmware answers it; a
// real-time round catches the drives up before its services look at them; without a batch nothing
// changes.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <utility>
#include <string>
#include <vector>

#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "tests/runtime/loopback_line_test.hpp"
#include "tests/support/dc_sine_line.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::runtime {
namespace {

constexpr Nanos kMs = 1'000'000;
constexpr std::uint8_t kBwr = 0x08;
constexpr std::uint16_t kAlControl = 0x0120;

class BatchedSteps : public test::LoopbackLineTest {
protected:
  BatchedSteps() : LoopbackLineTest({"a6b"}, 0) {}
  firmware::SlaveFirmware& drive() { return net_.firmware(0); }
};

TEST_F(BatchedSteps, AStepIsADeadlineOnlyOnceItHasWaitedTheBatch) {
  const Nanos step = drive().next_control_step();
  EXPECT_EQ(net_.next_deadline(), step) << "by default each control step wakes the loop";

  net_.set_control_step_batch(2 * kMs);
  EXPECT_EQ(net_.control_step_batch(), 2 * kMs);
  EXPECT_EQ(drive().next_deadline(), step + 2 * kMs) << "the step may wait 2 ms for a wake-up";

  net_.catch_up(step + kMs / 2);
  EXPECT_GT(drive().next_control_step(), step + kMs / 2) << "catch_up ran every step due by then";
  EXPECT_EQ(drive().next_deadline(), drive().next_control_step() + 2 * kMs);

  net_.set_control_step_batch(0);
  EXPECT_EQ(drive().next_deadline(), drive().next_control_step()) << "back to a deadline per step";
}

TEST_F(BatchedSteps, AnInterruptCatchesTheDriveUpBeforeTheFirmwareAnswers) {
  net_.set_control_step_batch(100 * kMs);  // far beyond this test: only the interrupt catches up
  run_until(net_, line_, clock_, 50 * kMs, counters_);
  const Nanos waiting = drive().next_control_step();
  ASSERT_LT(waiting, 50 * kMs) << "nothing woke the drive for 50 ms";

  // The master asks for Init: an AL Control write, i.e. an AL event interrupt.
  master_.send(test::ethercat_frame(kBwr, 0, kAlControl, std::vector<std::uint8_t>{0x01, 0x00}));
  run_pending(net_, line_, clock_, counters_);
  std::vector<std::uint8_t> reply(1514);
  ASSERT_GT(master_.receive(reply, 0), 0u);
  EXPECT_GT(drive().next_control_step(), 50 * kMs) << "the 400 steps that waited ran at the interrupt";
}

TEST_F(BatchedSteps, ARealTimeRoundCatchesTheDrivesUpBeforeItsServicesLook) {
  net_.set_control_step_batch(100 * kMs);
  clock_.set(30 * kMs);
  ASSERT_LT(drive().next_control_step(), 30 * kMs);

  struct Look final : LoopService {
    explicit Look(firmware::SlaveFirmware& f) : fw(f) {}
    void poll(Nanos) override { seen = fw.next_control_step(); }
    Nanos next_deadline() const override { return INT64_MAX; }
    firmware::SlaveFirmware& fw;
    Nanos seen = -1;
  } look(drive());
  serve_once(net_, line_, clock_, clock_.now(), counters_, &look);
  EXPECT_GT(look.seen, 30 * kMs) << "the service saw the drive as of its round";
}

// A frame may overtake a batch after any one step: the drives catch up one step each in turn,
// oldest first, with the hook between every two steps.
TEST(BatchedStepsCatchUp, TheDrivesCatchUpOneStepEachInTurn) {
  VirtualClock clock(0);
  network::Network net(std::vector<std::string>{"a6b", "ds5c1"}, clock);
  net.set_control_step_batch(10 * kMs);
  const Nanos period = 125'000;
  const Nanos first = net.firmware(0).next_control_step();
  ASSERT_EQ(net.firmware(1).next_control_step(), first);
  struct Record final : network::BetweenSlaves {
    explicit Record(network::Network& n) : net(n) {}
    void run() override { seen.push_back({net.firmware(0).next_control_step(), net.firmware(1).next_control_step()}); }
    network::Network& net;
    std::vector<std::pair<Nanos, Nanos>> seen;
  } record(net);
  clock.set(first + 2 * period);
  net.catch_up(clock.now(), &record);
  const std::vector<std::pair<Nanos, Nanos>> expected{
      {first + period, first},          {first + period, first + period},
      {first + 2 * period, first + period}, {first + 2 * period, first + 2 * period},
      {first + 3 * period, first + 2 * period}, {first + 3 * period, first + 3 * period}};
  EXPECT_EQ(record.seen, expected);
}

// The project master takes three drives to Op with DC at 1 ms and follows a sine for 400 cycles,
// once with every step at its instant and once with steps batched beyond the cycle (so SYNC0 and
// the frames' interrupts run them). The inputs it reads, cycle by cycle, are the same bytes.
std::vector<std::vector<std::uint8_t>> inputs_seen(Nanos batch) {
  master::test::VirtualLine line({"a6b", "ds5c1", "ds1000a"});
  line.network().set_control_step_batch(batch);
  master::Master m{line, line.clock()};
  EXPECT_EQ(m.scan(), 3u);
  test::DcSineLine dc(kMs);
  dc.op.cycles = 400;
  std::vector<std::vector<std::uint8_t>> seen;
  const auto program_inputs = dc.op.inputs;
  dc.op.inputs = [&](std::span<std::uint8_t> image) {
    seen.emplace_back(image.begin(), image.end());
    if (program_inputs) program_inputs(image);
  };
  const master::OpRunResult r = master::run_to_op(m, dc.op);
  EXPECT_TRUE(r.ok()) << r.error;
  return seen;
}

TEST(BatchedStepsInOp, TheMasterReadsTheSameInputsAsWithStepsOnTime) {
  const std::vector<std::vector<std::uint8_t>> on_time = inputs_seen(0);
  const std::vector<std::vector<std::uint8_t>> batched = inputs_seen(3 * kMs);
  ASSERT_GE(on_time.size(), 400u);
  ASSERT_EQ(batched.size(), on_time.size());
  std::size_t moving = 0;
  for (std::size_t c = 0; c < on_time.size(); ++c) {
    ASSERT_EQ(batched[c], on_time[c]) << "cycle " << c << " of " << on_time.size();
    if (c > 0 && on_time[c] != on_time[c - 1]) ++moving;
  }
  EXPECT_GT(moving, on_time.size() / 2) << "the drives moved: the inputs changed from cycle to cycle";
}

}  // namespace
}  // namespace vdrive::runtime
