// Lines whose process image does not fit one frame (72 drives and more), run by the project
// master in virtual time: the cyclic task sends the image as several LRWs in several frames, every
// drive reaches Op and follows a csp sine, the ESCs' working counters are the pieces' expected
// ones, and a lost frame or a wrong counter in any one piece makes its cycle wrong.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "esc_model/esc_faults.hpp"
#include "master/cyclic_task.hpp"
#include "master/datagram.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/csp_sine_run.hpp"
#include "tests/master/virtual_line.hpp"

namespace vdrive::master {
namespace {

// a6b, ds5c1, ds1000a, a6b, ... as the capacity benchmark mixes them.
std::vector<std::string> mixed_line(std::size_t n) {
  static const char* const kMix[] = {"a6b", "ds5c1", "ds1000a"};
  std::vector<std::string> ids;
  for (std::size_t i = 0; i < n; ++i) ids.emplace_back(kMix[i % 3]);
  return ids;
}

// The logical address of a frame's first datagram when it is an LRW, else ~0.
std::uint32_t lrw_address(std::span<const std::uint8_t> frame) {
  const std::size_t d = kEthernetHeaderSize + kEtherCatHeaderSize;
  if (frame.size() < d + kDatagramHeaderSize || frame[d] != static_cast<std::uint8_t>(Command::LRW)) return ~0u;
  return static_cast<std::uint32_t>(frame[d + 2] | (frame[d + 3] << 8) | (frame[d + 4] << 16) | (frame[d + 5] << 24));
}

TEST(SplitLine, HundredDrivesReachOpAndFollowACspSineOverSeveralFrames) {
  test::VirtualLine line{mixed_line(100)};
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 100u);
  master.set_mailbox_timeout(20'000'000);
  const test::CspSineRun run = test::run_csp_sine_at_1ms(master, 1'000'000'000);
  const OpRunResult& r = run.result;
  ASSERT_TRUE(r.reached_op) << r.error;
  ASSERT_GT(r.layout.size(), CycleFrames::kMaxLrwBytes) << "the image needs more than one frame";
  EXPECT_GT(r.stats.cycles, 1000u);
  EXPECT_EQ(r.stats.wrong_wkc, 0u);
  EXPECT_EQ(r.stats.lost_frames, 0u);
  EXPECT_EQ(r.left_op, 0u);
  EXPECT_EQ(r.stats.last_wkc, 300) << "the pieces' counters add up to 3 per drive";
  ASSERT_EQ(run.drives.size(), 100u);
  for (std::size_t i = 0; i < run.drives.size(); ++i) {
    SCOPED_TRACE(i);
    test::expect_drive_followed(run, i, [&] { return line.network().esc(i).peek_u16(0x0134); });
  }
}

class SplitLineInOp : public ::testing::Test {
protected:
  static constexpr std::size_t kDrives = 80;
  test::VirtualLine line{mixed_line(kDrives)};
  Master master{line, line.clock()};
  OpRunResult op;

  void SetUp() override {
    ASSERT_EQ(master.scan(), kDrives);
    master.set_mailbox_timeout(20'000'000);
    OpRunOptions o;
    o.cycle = 1'000'000;
    o.drift_frames = 200;
    o.mailbox_timeout = 20'000'000;
    o.cycles = 50;
    o.back_to_init = false;  // the test's own cyclic task takes over in Op
    op = run_to_op(master, o);
    ASSERT_TRUE(op.ok()) << op.error;
  }
};

TEST_F(SplitLineInOp, EachPieceComesBackWithTheCounterExpectedForIt) {
  CyclicTask task(master.transport(), op.layout, kDrives, 1'000'000, op.reference_station);
  ASSERT_GE(task.frames_per_cycle(), 2u);
  ASSERT_EQ(task.pieces().size(), task.frames_per_cycle());
  EXPECT_EQ(task.expected_wkc(), op.layout.expected_wkc) << "no window cut: the same total as one LRW";
  // Each piece expects +2 for every drive whose outputs the master put in it and +1 for every
  // drive whose inputs it put there (from the slaves' own records, not the layout's copy).
  std::uint32_t covered = 0;
  for (const LrwPiece& p : task.pieces()) {
    unsigned expected = 0;
    for (const Slave& s : master.slaves()) {
      const SlaveProcessData& pd = s.process_data;
      if (pd.output_logical >= p.logical && pd.output_logical + pd.output_bytes <= p.logical + p.bytes) expected += 2;
      if (pd.input_logical >= p.logical && pd.input_logical + pd.input_bytes <= p.logical + p.bytes) expected += 1;
    }
    EXPECT_EQ(p.expected_wkc, expected) << "piece at " << p.logical;
    EXPECT_EQ(p.logical, op.layout.logical_start + covered) << "contiguous";
    covered += p.bytes;
  }
  EXPECT_EQ(covered, op.layout.size());
  task.run(100);
  EXPECT_EQ(task.stats().wrong_wkc, 0u);
  EXPECT_EQ(task.stats().last_wkc, task.expected_wkc());
  EXPECT_TRUE(task.all_in(AlState::Op));
}

TEST_F(SplitLineInOp, ALostFrameOfAnyPieceMakesItsCycleWrong) {
  CyclicTask task(master.transport(), op.layout, kDrives, 1'000'000, op.reference_station);
  ASSERT_GE(task.frames_per_cycle(), 2u);
  int inputs = 0;
  task.on_inputs([&](std::span<std::uint8_t>) { ++inputs; });
  task.run(20);
  ASSERT_EQ(task.stats().wrong_wkc, 0u);
  task.reset_stats();
  inputs = 0;
  const std::uint32_t second = task.pieces()[1].logical;
  line.drop_reply = [&](std::span<const std::uint8_t> reply) { return lrw_address(reply) == second; };
  task.run(3);
  EXPECT_EQ(task.stats().cycles, 3u);
  EXPECT_EQ(task.stats().wrong_wkc, 3u);
  EXPECT_EQ(task.stats().lost_frames, 3u) << "one frame of each cycle";
  EXPECT_EQ(inputs, 0) << "a cycle with a piece missing hands no inputs over";
  EXPECT_EQ(task.stats().al_wkc, kDrives) << "frame 0 (BRD) still came back";
  line.drop_reply = {};
  task.run(20);
  EXPECT_EQ(task.stats().wrong_wkc, 3u) << "right again once the frames come back";
  EXPECT_EQ(inputs, 20);
}

TEST_F(SplitLineInOp, AWrongCounterInOnePieceMakesItsCycleWrong) {
  CyclicTask task(master.transport(), op.layout, kDrives, 1'000'000, op.reference_station);
  task.run(10);
  ASSERT_EQ(task.stats().wrong_wkc, 0u);
  // The last drive's ESC stops counting: the pieces holding its outputs and its inputs (the last
  // of each half) come back 2 and 1 short, the others as expected.
  line.network().esc(kDrives - 1).set_faults({.wkc_error = true});
  task.reset_stats();
  task.run(3);
  EXPECT_EQ(task.stats().wrong_wkc, 3u);
  EXPECT_EQ(task.stats().lost_frames, 0u);
  EXPECT_EQ(task.stats().last_wkc, task.expected_wkc() - 3);
  line.network().esc(kDrives - 1).set_faults({});
}

}  // namespace
}  // namespace vdrive::master
