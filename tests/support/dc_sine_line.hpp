#pragma once
// What the steady-state tests run: the project master takes the line to Op with DC at `cycle`
// (SYNC0 at the cycle, 200 drift frames) and stays there, every drive enabled in csp and following
// a sine that outlasts any test (100 ms of settling, then 60 s), so done() stays false.
// The test sets op.cycles (its warm-up in Op), then runs its own CyclicTask on op.outputs/inputs.
#include <cstdint>

#include "common/clock.hpp"
#include "master/cia402_program.hpp"
#include "master/op_run.hpp"

namespace vdrive::test {

struct DcSineLine {
  static master::SineProgramOptions sine_options(Nanos cycle) {
    master::SineProgramOptions sine;
    sine.cycle = cycle;
    sine.settle = 100'000'000;
    sine.motion = 60'000'000'000;
    return sine;
  }

  explicit DcSineLine(Nanos cycle) : program(sine_options(cycle)) {
    op.cycle = cycle;
    op.dc = true;
    op.drift_frames = 200;
    op.mailbox_timeout = 20'000'000;
    op.back_to_init = false;
    program.attach(op);
  }
  DcSineLine(const DcSineLine&) = delete;  // op's callbacks point at this program
  DcSineLine& operator=(const DcSineLine&) = delete;

  master::SineProgram program;
  master::OpRunOptions op;
};

}  // namespace vdrive::test
