#include "vdrive/drive/modes/profile_sin2_move.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vdrive::drive {

void Sin2Move::add_phase(double duration, double v1) {
  if (duration <= 0.0 || count_ >= phases_.size()) return;
  const double start = count_ == 0 ? 0.0 : phases_[count_ - 1].start + phases_[count_ - 1].duration;
  const MotionState from = end_;
  phases_[count_++] = Phase{start, duration, from.position, from.velocity, v1 - from.velocity};
  end_ = eval(phases_[count_ - 1], duration);
}

MotionState Sin2Move::eval(const Phase& ph, double tau) const {
  const double T = ph.duration;
  const double x = std::numbers::pi * tau / T;
  const double s = std::sin(0.5 * x);
  return {ph.p0 + ph.v0 * tau + ph.dv * (0.5 * tau - T / (2.0 * std::numbers::pi) * std::sin(x)),
          ph.v0 + ph.dv * s * s};
}

void Sin2Move::plan(MotionState from, double target, double vmax, double acc, double dec) {
  target_ = target;
  vmax_ = std::max(vmax, 0.0);
  acc_ = acc > 0.0 ? acc : 1.0;
  dec_ = dec > 0.0 ? dec : 1.0;
  count_ = 0;
  t_ = 0.0;
  end_ = from;
  replan_after_ = false;
  done_ = false;

  const double remaining = target - from.position;
  const double dir = remaining >= 0.0 ? 1.0 : -1.0;
  const double u = from.velocity * dir;  // speed toward the target
  const double distance = std::abs(remaining);
  if (u < 0.0 || u * u / (2.0 * dec_) > distance) {
    // Moving away, or too fast to stop on the target: stop first, then plan back from there.
    add_phase(std::abs(from.velocity) / dec_, 0.0);
    replan_after_ = true;
    return;
  }
  if (vmax_ <= 0.0) {  // no speed allowed: just stop
    add_phase(std::abs(from.velocity) / dec_, 0.0);
    return;
  }
  // Cruise speed: the highest the distance allows (acc up from u, dec down to 0), at most vmax.
  double vc = std::sqrt((distance + u * u / (2.0 * acc_)) / (1.0 / (2.0 * acc_) + 1.0 / (2.0 * dec_)));
  vc = std::min(vc, vmax_);
  const double rate1 = vc >= u ? acc_ : dec_;
  const double t1 = std::abs(vc - u) / rate1;
  const double d1 = 0.5 * (u + vc) * t1;
  const double t3 = vc / dec_;
  const double d3 = 0.5 * vc * t3;
  const double d2 = std::max(0.0, distance - d1 - d3);
  add_phase(t1, vc * dir);
  if (vc > 0.0) add_phase(d2 / vc, vc * dir);
  add_phase(t3, 0.0);
}

MotionState Sin2Move::step(double dt) {
  if (done_) return {target_, 0.0};
  t_ += dt;
  for (std::size_t i = 0; i < count_; ++i) {
    const Phase& ph = phases_[i];
    if (t_ < ph.start + ph.duration) return eval(ph, t_ - ph.start);
  }
  // All phases run out.
  if (replan_after_) {
    const double overrun = t_ - (count_ ? phases_[count_ - 1].start + phases_[count_ - 1].duration : 0.0);
    plan({end_.position, 0.0}, target_, vmax_, acc_, dec_);
    return overrun > 0.0 ? step(overrun) : MotionState{end_.position, 0.0};
  }
  done_ = true;
  return {target_, 0.0};
}

}  // namespace vdrive::drive
