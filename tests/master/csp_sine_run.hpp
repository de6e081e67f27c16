#pragma once
// The project master takes a scanned line to Op with DC at 1 ms (SYNC0 at the cycle, 200 drift
// frames) and runs a 1 Hz csp sine on every drive for `motion`; the run's result and each drive's
// verdict come back for the test to judge.
#include <vector>

#include "common/clock.hpp"
#include "master/cia402_program.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"

namespace vdrive::master::test {

struct CspSineRun {
  OpRunResult result;
  std::vector<DriveResult> drives;
};

inline CspSineRun run_csp_sine_at_1ms(Master& master, Nanos motion) {
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
  CspSineRun run;
  run.result = run_to_op(master, options);
  run.drives = program.results();
  return run;
}

}  // namespace vdrive::master::test
