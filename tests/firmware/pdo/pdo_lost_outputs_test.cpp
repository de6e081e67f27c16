// A SYNC0 with no outputs written since the last one is a lost set-point, not a repeated one
// (vdrive/firmware/pdo/process_data_module.hpp): the A6B bridges it with the last increment
// (command compensation, L16880-L16917) instead of standing still for a cycle. Drives an A6B in
// csp with DC at 1 ms from the project master's sine program in virtual time, then leaves out
// the master's frame for one cycle at a time while the axis moves, and compares the drive's own
// following error (60F4h) and position demand (6062h) around each gap with their steady values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "master/cia402_program.hpp"
#include "tests/support/dc_sine_line.hpp"
#include "master/cyclic_task.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive {
namespace {

TEST(PdoLostOutputs, A6bBridgesACycleWithNoFrameInsteadOfHoldingTheTarget) {
  constexpr Nanos kCycle = 1'000'000;
  master::test::VirtualLine line({"a6b"});
  master::Master m{line, line.clock()};
  ASSERT_EQ(m.scan(), 1u);

  test::DcSineLine dc(kCycle);
  master::OpRunOptions& op = dc.op;
  const master::SineProgram& program = dc.program;
  op.cycles = 300;  // enabled, settled, moving
  const master::OpRunResult result = master::run_to_op(m, op);
  ASSERT_TRUE(result.ok()) << result.error;
  ASSERT_NE(result.reference_station, 0) << "DC must be running";

  master::CyclicTask task(m.transport(), result.layout, 1, kCycle, result.reference_station);
  task.on_outputs(op.outputs);
  task.on_inputs(op.inputs);
  od::ObjectStore& objects = line.network().firmware(0).objects();
  const drive::ObjectRef<std::int32_t> following_error_value(objects, 0x60F4), demand_value(objects, 0x6062);
  auto following_error = [&] { return std::abs(static_cast<std::int64_t>(following_error_value.get())); };
  auto demand = [&] { return demand_value.get(); };
  Nanos next = line.clock().now();
  auto cycle = [&](bool send) {
    if (send) task.run_cycle();
    next += kCycle;
    line.receive({}, next - line.clock().now());
  };

  std::int64_t steady = 0;
  for (int i = 0; i < 200; ++i) {
    cycle(true);
    steady = std::max(steady, following_error());
  }
  ASSERT_GT(steady, 0);
  // A gap every 10 cycles, at every phase of the motion; only where the axis moves fast enough
  // for the comparison to mean something.
  int gaps = 0, bridged = 0;
  std::int64_t around_gaps = 0;
  for (int k = 0; k < 40; ++k) {
    for (int i = 0; i < 8; ++i) cycle(true);
    const std::int32_t d0 = demand();
    cycle(true);
    const std::int32_t d1 = demand();
    cycle(false);
    const std::int32_t d2 = demand();
    const std::int64_t normal = static_cast<std::int64_t>(d1) - d0, in_gap = static_cast<std::int64_t>(d2) - d1;
    if (std::abs(normal) > 5000) {
      ++gaps;
      if (4 * std::abs(in_gap - normal) <= std::abs(normal)) ++bridged;  // within 25 % of a normal cycle's travel
    }
    for (int i = 0; i < 3; ++i) {
      around_gaps = std::max(around_gaps, following_error());
      cycle(true);
    }
  }
  ASSERT_GE(gaps, 20);
  EXPECT_EQ(bridged, gaps) << "the position demand did not go on through a cycle with no frame";
  EXPECT_LT(around_gaps, steady * 3 / 2) << "steady " << steady;
  ASSERT_EQ(program.results().size(), 1u);
  EXPECT_FALSE(program.results()[0].faulted);
}

}  // namespace
}  // namespace vdrive
