// Steady state allocates nothing (architecture rule): a line of the three products in Op
// with DC at 1 ms, every drive enabled in cyclic synchronous position and following a sine with
// its default plant, the project master's CiA 402 program exchanging process data every cycle
// (LRW + FRMW of the DC reference time + BRD AL status). Over 10,000 cycles after warm-up, the
// whole cycle — the master's frame, the frame through the segment and the ESCs, the firmware's
// IRQs (PDO exchange, sync, mailbox), the SYNC0 and watchdog timers, the drive engines' control
// steps and the plants' ODE steps — calls operator new zero times. Counts with tests/support/allocation_counter.hpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "master/cia402_program.hpp"
#include "tests/support/dc_sine_line.hpp"
#include "master/cyclic_task.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "tests/support/allocation_counter.hpp"


namespace vdrive {
namespace {

TEST(SteadyStateNoAllocation, ThreeDrivesInCspWithDcAndPlantsAllocateNothing) {
  constexpr Nanos kCycle = 1'000'000;
  master::test::VirtualLine line({"a6b", "ds5c1", "ds1000a"});
  master::Master m{line, line.clock()};
  ASSERT_EQ(m.scan(), 3u);

  test::DcSineLine dc(kCycle);  // the sine outlasts the test: the drives keep moving throughout
  master::OpRunOptions& op = dc.op;
  const master::SineProgram& program = dc.program;
  op.cycles = 1000;  // warm-up in Op: enabling, settle, the sine under way
  const master::OpRunResult result = master::run_to_op(m, op);
  ASSERT_TRUE(result.ok()) << result.error;
  ASSERT_NE(result.reference_station, 0) << "DC must be running";

  // The same cyclic task as run_to_op's, continuing where it stopped; built before counting.
  master::CyclicTask task(m.transport(), result.layout, m.slaves().size(), kCycle, result.reference_station);
  task.on_outputs(op.outputs);
  task.on_inputs(op.inputs);
  // One bus cycle: the frame, then the line's timers up to the start of the next cycle.
  Nanos next = line.clock().now();
  auto cycle = [&] {
    task.run_cycle();
    next += kCycle;
    line.receive({}, next - line.clock().now());
  };
  for (int i = 0; i < 100; ++i) cycle();  // first use of everything the task touches

  const std::uint64_t frames_before = line.counters().frames_out.load();
  const long before = vdrive::test::allocation_count();
  for (int k = 0; k < 10'000; ++k) cycle();
  const long allocations = vdrive::test::allocation_count() - before;

  EXPECT_EQ(allocations, 0) << "operator new calls in 10,000 steady-state cycles";
  // It was steady state: every frame came back with the right working counter, the line stayed
  // in Op, and every drive was enabled and moving without a fault.
  EXPECT_EQ(task.stats().wrong_wkc, 0u);
  EXPECT_EQ(task.stats().lost_frames, 0u);
  EXPECT_TRUE(task.all_in(master::AlState::Op));
  EXPECT_GE(line.counters().frames_out.load() - frames_before, 10'000u);
  ASSERT_EQ(program.results().size(), 3u);
  for (const master::DriveResult& r : program.results()) {
    EXPECT_TRUE(r.enabled) << r.station;
    EXPECT_FALSE(r.faulted) << r.station;
    EXPECT_GT(r.samples, 10'000u) << r.station;
    EXPECT_LE(r.max_following_error, r.following_window) << r.station;
  }
}

}  // namespace
}  // namespace vdrive
