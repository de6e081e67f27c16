#pragma once
// A point-to-point move whose speed changes follow a sin^2 curve instead of a straight line
// (6086h = 1 on the DS1000A-EC, L1831-L1834). Each speed change from v0 to v1 takes as long as the
// linear ramp would (|v1 - v0| / rate), so the set acceleration is the mean one and the peak is
// pi/2 times it; the velocity is v0 + (v1 - v0) sin^2(pi t / 2T), smooth at both ends.
// Because a sin^2 ramp covers the same distance as the linear one of equal duration, the move is
// planned like a trapezoid: [brake to 0 when moving away or unable to stop in time] -> change to the
// cruise speed -> cruise -> stop on the target. plan() may be called at any step (new target, new
// speed, halt released); step() allocates nothing.
#include <array>
#include <cstddef>

#include "vdrive/drive/motion_ramp.hpp"

namespace vdrive::drive {

class Sin2Move {
public:
  // Plans from `from` to `target` with speed limit vmax and mean acceleration/deceleration acc/dec
  // (all > 0).
  void plan(MotionState from, double target, double vmax, double acc, double dec);

  // Advances by dt and returns the new state; ends exactly on the target with zero velocity.
  MotionState step(double dt);

  bool done() const { return done_; }
  double target() const { return target_; }

private:
  struct Phase {
    double start = 0.0;     // time since plan() (s)
    double duration = 0.0;  // s
    double p0 = 0.0, v0 = 0.0, dv = 0.0;
  };
  void add_phase(double duration, double v1);
  MotionState eval(const Phase& ph, double tau) const;

  std::array<Phase, 4> phases_{};
  std::size_t count_ = 0;
  double t_ = 0.0;
  double target_ = 0.0, vmax_ = 0.0, acc_ = 1.0, dec_ = 1.0;
  bool replan_after_ = false;  // the plan ends in a brake to 0; plan again from there
  bool done_ = true;
  MotionState end_{};
};

}  // namespace vdrive::drive
