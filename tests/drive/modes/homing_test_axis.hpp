#pragma once
// A test axis for HomingMode: a real product's dictionary and a line with switches, index marks
// and hard stops at known true positions (x). It plays the engine's part in miniature: samples the
// axis, calls step()/idle(), re-references on take_home_found (6064h = 607Ch at that point) and
// moves the axis as the set-point asks (Velocity: integrate; Position: follow exactly), stopping
// it at a hard stop, where the torque rises to the set-point's torque limit.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/modes/homing_mode.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/drive/unit_scaling.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive::testing {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct AxisLayout {
  double negative_limit = -kInf;                  // NOT active for x <= this
  double positive_limit = kInf;                   // POT active for x >= this
  std::vector<std::pair<double, double>> home;    // HOME active for lo <= x <= hi
  double index_period = 250.0;                    // an index mark every period ...
  double index_phase = 25.0;                      // ... at phase + k * period
  double hard_stop_low = -kInf, hard_stop_high = kInf;
};

class HomingTestAxis {
public:
  explicit HomingTestAxis(const std::string& product, AxisLayout layout = {})
      : profile_(profile::load_profile(product)), dict_(od::shared_dictionary(profile_)), store_(*dict_),
        layout_(std::move(layout)) {
    units_.apply({10000, 1, 1, 1, 10000, 1, 0});  // 1 user unit = 1 increment, 10000 per turn
    mode_ = std::make_unique<HomingMode>(ctx_);
    speeds(2000, 200);
    set(0x609A, 0, 100000);
  }

  HomingMode& mode() { return *mode_; }
  const profile::ProductProfile& product() const { return profile_; }

  // Writes an object of the product (absent ones are ignored, like ObjectRef).
  void set(std::uint16_t index, std::uint8_t sub, std::int64_t value) {
    ObjectRef<std::int64_t>(store_, index, sub).set(value);
  }
  void method(std::int8_t m) { set(0x6098, 0, m); }
  void speeds(std::int64_t search_switch, std::int64_t search_zero) {
    set(0x6099, 1, search_switch);
    set(0x6099, 2, search_zero);
  }

  // Puts the axis at true position x, standing; user position = x (not referenced yet).
  void place(double x) {
    x_ = x;
    frame_ = 0.0;
    demand_ = x;
    velocity_ = 0.0;
    torque_ = 0.0;
  }

  // One control step with `controlword`; enabled = Operation enabled (else idle()).
  void tick(std::uint16_t controlword, bool enabled = true) {
    const AxisSample s = sample();
    Setpoint sp{Setpoint::Kind::Position, demand_, 0.0};
    if (enabled) {
      if (!was_enabled_) mode_->activate(s);
      sp = mode_->step(s, controlword);
    } else {
      mode_->idle(s, controlword);
      sp = {Setpoint::Kind::Position, x_ + frame_, 0.0};
    }
    was_enabled_ = enabled;
    double found = 0.0;
    if (mode_->take_home_found(found)) {
      // The engine's preset: the found point reads 607Ch from now on.
      const double shift = static_cast<double>(ObjectRef<std::int32_t>(store_, 0x607C).get()) - found;
      frame_ += shift;
      demand_ += shift;
      sp.position += shift;
      ++homes_found_;
    }
    const std::string_view alarm = mode_->pending_alarm();
    if (!alarm.empty()) alarm_ = std::string(alarm);
    move(sp);
    time_ += dt_ns_;
  }

  // Runs with `controlword` until the mode is idle again (or `seconds` pass); true when it ended.
  bool run(std::uint16_t controlword, double seconds = 60.0, bool enabled = true) {
    const int steps = static_cast<int>(seconds * 1000.0);
    for (int i = 0; i < steps; ++i) {
      tick(controlword, enabled);
      if (mode_->phase() == HomingMode::Phase::Idle) return true;
    }
    return false;
  }

  // The usual master sequence: bit 4 low for a step, then high until the run ends.
  bool home(double seconds = 60.0, bool enabled = true) {
    tick(enabled ? 0x000F : 0x0007, enabled);
    return run(enabled ? 0x001F : 0x0007 | 0x0010, seconds, enabled);
  }

  std::uint16_t bits() const { return mode_->status_bits() & (1u << 13 | 1u << 12 | 1u << 10); }
  // The true position that reads `user` (6064h) now: where the reference point is.
  double true_of(double user) const { return user - frame_; }
  double x() const { return x_; }
  double user_position() const { return x_ + frame_; }
  int homes_found() const { return homes_found_; }
  const std::string& alarm() const { return alarm_; }
  double max_torque_limit_seen() const { return max_torque_limit_; }

private:
  std::uint32_t inputs_at(double x) const {
    std::uint32_t in = 0;
    if (x <= layout_.negative_limit) in |= din::negative_limit;
    if (x >= layout_.positive_limit) in |= din::positive_limit;
    for (const auto& [lo, hi] : layout_.home)
      if (x >= lo && x <= hi) in |= din::home;
    return in;
  }

  AxisSample sample() const {
    AxisSample s;
    s.time = time_;
    s.dt_s = dt_ns_ * 1e-9;
    s.position = x_ + frame_;
    s.velocity = velocity_;
    s.torque = torque_;
    s.position_demand = demand_;
    s.velocity_demand = demand_velocity_;
    s.inputs = inputs_at(x_);
    s.index_passed = index_passed_;
    s.index_position = index_x_ + frame_;
    s.stopped = std::abs(velocity_) < 1e-6;
    return s;
  }

  void move(const Setpoint& sp) {
    const double dt = dt_ns_ * 1e-9;
    if (sp.kind == Setpoint::Kind::Velocity) {
      demand_ += sp.velocity * dt;
      demand_velocity_ = sp.velocity;
    } else {
      demand_velocity_ = (sp.position - demand_) / dt;
      demand_ = sp.position;
    }
    if (sp.torque_limit > max_torque_limit_) max_torque_limit_ = sp.torque_limit;
    const double x0 = x_;
    double x1 = demand_ - frame_;
    torque_ = 0.0;
    if (x1 < layout_.hard_stop_low) {
      x1 = layout_.hard_stop_low;
      torque_ = -(sp.torque_limit > 0.0 ? sp.torque_limit : 3000.0);
    } else if (x1 > layout_.hard_stop_high) {
      x1 = layout_.hard_stop_high;
      torque_ = sp.torque_limit > 0.0 ? sp.torque_limit : 3000.0;
    }
    x_ = x1;
    velocity_ = (x1 - x0) / dt;
    // Index marks crossed on the way (the last one, moving either way).
    index_passed_ = false;
    if (layout_.index_period > 0.0 && x1 != x0) {
      const double lo = std::min(x0, x1), hi = std::max(x0, x1);
      const double k_lo = std::ceil((lo - layout_.index_phase) / layout_.index_period);
      const double k_hi = std::floor((hi - layout_.index_phase) / layout_.index_period);
      if (k_lo <= k_hi) {
        index_passed_ = true;
        const double k = x1 > x0 ? k_lo : k_hi;  // the first one met
        index_x_ = layout_.index_phase + k * layout_.index_period;
      }
    }
  }

  profile::ProductProfile profile_;
  std::shared_ptr<const od::Dictionary> dict_;
  od::ObjectStore store_;
  UnitScaling units_;
  DriveContext ctx_{profile_, store_, units_};
  std::unique_ptr<HomingMode> mode_;
  AxisLayout layout_;
  Nanos time_ = 0;
  Nanos dt_ns_ = 1'000'000;
  double x_ = 0.0, frame_ = 0.0, demand_ = 0.0, demand_velocity_ = 0.0, velocity_ = 0.0, torque_ = 0.0;
  bool index_passed_ = false;
  double index_x_ = 0.0;
  bool was_enabled_ = false;
  int homes_found_ = 0;
  std::string alarm_;
  double max_torque_limit_ = 0.0;
};

}  // namespace vdrive::drive::testing
