// As a new user would: the project master takes the line of three drives to Op with DC at 1 ms,
// enables each in cyclic synchronous position (CiA 402 program, master/cia402_program.hpp) and
// commands a sine; each drive's position actual must follow within its following-error window
// 6065h, with no fault. Virtual time: the drives move their plants for real.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "master/cia402_program.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/csp_sine_run.hpp"
#include "tests/master/virtual_line.hpp"

namespace vdrive::master {
namespace {

TEST(Cia402Sine, EachDriveFollowsASineInCspAt1msDc) {
  test::VirtualLine line({"a6b", "ds5c1", "ds1000a"});
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 3u);
  master.set_mailbox_timeout(20'000'000);

  const test::CspSineRun run = test::run_csp_sine_at_1ms(master, 2'000'000'000);
  const OpRunResult& result = run.result;
  ASSERT_TRUE(result.reached_op) << result.error;
  EXPECT_EQ(result.stats.wrong_wkc, 0u);
  EXPECT_EQ(result.left_op, 0u);
  ASSERT_EQ(run.drives.size(), 3u);
  for (const DriveResult& r : run.drives) {
    std::printf("drive 0x%04X: amplitude %.0f, max |60F4h| %lld, 6065h %u, %llu samples, 6041h %04X, 603Fh %04X %s\n",
                r.station, r.amplitude, static_cast<long long>(r.max_following_error), r.following_window,
                static_cast<unsigned long long>(r.samples), r.statusword, r.error_code, r.note.c_str());
    EXPECT_TRUE(r.enabled) << r.station;
    EXPECT_FALSE(r.faulted) << r.station << " 603Fh " << std::hex << r.error_code;
    EXPECT_GE(r.samples, 1900u) << r.station;
    EXPECT_GT(r.amplitude, 0.0) << r.station;
    EXPECT_LE(r.max_following_error, r.following_window) << r.station;
    EXPECT_GT(r.max_following_error, 0) << r.station << ": a moving axis lags a little";
  }
}

// --revolutions: the amplitude is that many of each drive's own motor revolutions (6091h/6092h),
// so the same fraction on drives with very different user units.
TEST(Cia402Sine, RevolutionsScaleEachDrivesOwnRevolution) {
  std::vector<double> amplitudes[2];
  const double revolutions[2] = {1.0, 0.25};
  for (int run = 0; run < 2; ++run) {
    test::VirtualLine line({"a6b", "ds5c1", "ds1000a"});
    Master master{line, line.clock()};
    ASSERT_EQ(master.scan(), 3u);
    SineProgramOptions sine;
    sine.revolutions = revolutions[run];
    sine.motion = 100'000'000;
    SineProgram program(sine);
    OpRunOptions options;
    options.dc = true;
    options.drift_frames = 200;
    options.mailbox_timeout = 20'000'000;
    program.attach(options);
    options.cycles = 2000;
    ASSERT_TRUE(run_to_op(master, options).reached_op);
    for (const DriveResult& r : program.results()) {
      EXPECT_TRUE(r.ok()) << r.station << " at " << revolutions[run] << " rev";
      amplitudes[run].push_back(r.amplitude);
    }
  }
  ASSERT_EQ(amplitudes[0].size(), 3u);
  ASSERT_EQ(amplitudes[1].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(amplitudes[0][i], 0.0);
    EXPECT_DOUBLE_EQ(amplitudes[1][i], amplitudes[0][i] / 4) << "drive " << i;
  }
}

}  // namespace
}  // namespace vdrive::master

namespace vdrive::master {
namespace {

// A drive's line says why it failed, first cause first, with the units of its numbers.
TEST(DriveResultLine, AFailedDriveSaysWhy) {
  DriveResult r;
  r.position = 1;
  r.station = 0x1002;
  r.name = "DS5C1";
  r.following_window = 100000;
  r.amplitude = 131072;
  EXPECT_EQ(describe(r).rfind("slave 2 @0x1002 DS5C1: FAILED (never reached Operation enabled), amplitude 131072, ", 0), 0u)
      << describe(r);
  r.enabled = true;
  r.faulted = true;
  r.error_code = 0xFF10;
  EXPECT_NE(describe(r).find(": FAILED (faulted, 603Fh FF10h), "), std::string::npos) << describe(r);
  r.faulted = false;
  EXPECT_NE(describe(r).find(": FAILED (no sine cycle measured), "), std::string::npos) << describe(r);
  r.samples = 2000;
  r.max_following_error = 100001;
  EXPECT_NE(describe(r).find(": FAILED (following error 100001 beyond the window 100000), "), std::string::npos)
      << describe(r);
  r.max_following_error = 5123;
  EXPECT_EQ(describe(r), "slave 2 @0x1002 DS5C1: ok, amplitude 131072, max following error 5123 (window 6065h = 100000; "
                         "position units of 6064h) over 2000 cycles, statusword 0x0000, 603Fh 0xFF10");
}

}  // namespace
}  // namespace vdrive::master
