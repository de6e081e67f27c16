#pragma once
// The project master takes a scanned line to Op with DC at 1 ms (SYNC0 at the cycle, 200 drift
// frames) and runs a 1 Hz csp sine on every drive for `motion`; the run's result and each drive's
// verdict come back for the test to judge.
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "common/clock.hpp"
#include "master/cia402_program.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"

namespace vdrive::master::test {

struct CspSineRun {
  OpRunResult result;
  std::vector<DriveResult> drives;
};

// `adjust` (optional) sees the options last, e.g. to wrap the program's outputs/inputs.
inline CspSineRun run_csp_sine_at_1ms(Master& master, Nanos motion,
                                      const std::function<void(OpRunOptions&)>& adjust = {}) {
  SineProgramOptions sine;
  sine.cycle = 1'000'000;
  sine.frequency_hz = 1.0;
  sine.motion = motion;
  SineProgram program(sine);
  OpRunOptions options;
  options.cycle = 1'000'000;
  options.dc = true;
  options.drift_frames = 200;
  options.mailbox_timeout = 20'000'000;
  program.attach(options);
  options.cycles = program.cycles_needed(options.cycle);
  if (adjust) adjust(options);
  CspSineRun run;
  run.result = run_to_op(master, options);
  run.drives = program.results();
  return run;
}

// The whole run in Op with no wrong working counter, and drive `i` enabled, not faulted, following
// the sine within its following-error window. `al_code` is read when Op was not reached.
inline void expect_drive_followed(const CspSineRun& run, std::size_t i, const std::function<std::uint16_t()>& al_code) {
  const OpRunResult& result = run.result;
  ASSERT_TRUE(result.reached_op) << result.error << " AL status code 0x" << std::hex << al_code();
  EXPECT_EQ(result.stats.wrong_wkc, 0u);
  EXPECT_EQ(result.left_op, 0u);
  ASSERT_LT(i, run.drives.size());
  const DriveResult& r = run.drives[i];
  EXPECT_TRUE(r.enabled) << describe(r);
  EXPECT_FALSE(r.faulted) << describe(r);
  EXPECT_EQ(r.statusword & 0x006F, 0x0027) << describe(r);  // Operation enabled
  EXPECT_GE(r.samples, 900u) << describe(r);
  EXPECT_GT(r.max_following_error, 0) << describe(r) << ": a moving axis lags a little";
  EXPECT_LE(r.max_following_error, r.following_window) << describe(r);
}

// A line of one drive: scanned, taken to Op and following a 1 s csp sine.
inline void expect_lone_drive_follows_csp_sine(VirtualLine& line) {
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 1u);
  master.set_mailbox_timeout(20'000'000);
  const CspSineRun run = run_csp_sine_at_1ms(master, 1'000'000'000);
  ASSERT_EQ(run.drives.size(), 1u);
  expect_drive_followed(run, 0, [&] { return line.network().esc(0).peek_u16(0x0134); });
}

}  // namespace vdrive::master::test
