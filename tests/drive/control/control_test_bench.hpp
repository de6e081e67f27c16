#pragma once
// A drive axis for the control-loop and cyclic-mode tests: a real product profile and object
// store, 10000 user units per motor revolution, the product's default plant (drive::default_plant)
// stepped once per control period, the product's ControlLoop, and a mode fed by a "master" that
// writes its targets once per bus cycle. Gains are pinned to known values unless a test asks for
// the product's own, so tracking bounds can be derived by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <string>

#include "plant/plant.hpp"
#include "vdrive/drive/control/control_loop.hpp"
#include "vdrive/drive/control/motor_setpoint.hpp"
#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/drive/product_plant.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive::test {

inline constexpr double kUserPerRev = 10000.0;

// Known gains: Kp 100/s, f_v 50 Hz, Ti = 2/(pi f_v), torque filter 0.2 ms, ratio 1 (the default
// plant's load equals the rotor), full velocity feed-forward.
struct PinnedGains {
  double kp = 100.0, fv = 50.0, ti = 2.0 / (std::numbers::pi * 50.0), tf = 0.2e-3, ratio = 1.0, kff = 1.0;
};

inline void pin_gains(profile::ProductProfile& p, const PinnedGains& g = {}) {
  auto fixed = [](double v) { return profile::ParameterRef{0, 0, 1.0, v}; };
  p.drive.gains.position_gain = fixed(g.kp);
  p.drive.gains.velocity_gain = fixed(g.fv);
  p.drive.gains.velocity_integral = fixed(g.ti);
  p.drive.gains.torque_filter = fixed(g.tf);
  p.drive.gains.inertia_ratio = fixed(g.ratio);
  p.drive.gains.velocity_feedforward = fixed(g.kff);
}

class AxisBench {
public:
  using Tweak = std::function<void(profile::ProductProfile&)>;

  explicit AxisBench(const std::string& id, const Tweak& tweak = {}, bool pinned_gains = true)
      : profile_(load(id, tweak, pinned_gains)), dictionary_(od::shared_dictionary(profile_)), store_(*dictionary_),
        ctx_{profile_, store_, units_}, plant_(description()) {
    units_.apply({static_cast<std::uint32_t>(kUserPerRev), 1, 1, 1, static_cast<std::uint32_t>(kUserPerRev), 1, 0});
    motor_ = drive::default_motor(profile_);
    loop_ = make_control_loop(ctx_, motor_);
    dt_ = static_cast<Nanos>(profile_.drive.control_period_ns);
  }

  const profile::ProductProfile& profile() const { return profile_; }
  od::ObjectStore& store() { return store_; }
  const DriveContext& ctx() const { return ctx_; }
  const UnitScaling& units() const { return units_; }
  plant::Plant& plant() { return plant_; }
  const plant::MotorParams& motor() const { return motor_; }
  ControlLoop& loop() { return *loop_; }
  Nanos now() const { return now_; }
  Nanos control_period() const { return dt_; }
  const AxisSample& sample() const { return sample_; }
  const Setpoint& last_setpoint() const { return last_; }
  const plant::AxisFeedback& feedback() const { return plant_.feedback(0); }

  template <typename T>
  void set(std::uint16_t index, std::uint8_t sub, T value) {
    ObjectRef<T>(store_, index, sub).set(value);
  }

  double position_user() const { return units_.position_to_user(feedback().motor_angle_rad); }
  double velocity_user() const { return units_.velocity_to_user(feedback().motor_velocity_rad_s); }
  double rpm() const { return feedback().motor_velocity_rad_s * 60.0 / (2.0 * std::numbers::pi); }

  // Power stage on in `mode`: the loop starts from the axis, the mode from the demand.
  void enable(ModeHandler& mode) {
    loop_->reset(feedback());
    sample_ = make_sample();
    sample_.position_demand = sample_.position;
    last_.position = sample_.position;
    mode.activate(sample_);
  }

  // One control step of `mode`; on a bus-cycle boundary `master(now)` writes the outputs first
  // and, when `announce` is set, the engine tells the mode (on_cycle).
  void step(ModeHandler& mode, std::uint16_t controlword, const std::function<void(Nanos)>& master = {},
            Nanos bus_cycle = 1'000'000, bool announce = true) {
    if (master && now_ % bus_cycle == 0) {
      master(now_);
      if (announce) mode.on_cycle(now_);
    }
    sample_ = make_sample();
    last_ = mode.step(sample_, controlword);
    const MotorSetpoint m = to_motor_setpoint(last_, units_, motor_.rated_torque_nm, 0.0, 0.0);
    plant_.command(0, loop_->step(m, feedback(), sample_.dt_s));
    now_ += dt_;
    plant_.advance_to(now_);
  }

  // Runs for `duration`, calling `check` after every step.
  void run(ModeHandler& mode, Nanos duration, std::uint16_t controlword, const std::function<void(Nanos)>& master = {},
           const std::function<void()>& check = {}, Nanos bus_cycle = 1'000'000, bool announce = true) {
    const Nanos end = now_ + duration;
    while (now_ < end) {
      step(mode, controlword, master, bus_cycle, announce);
      if (check) check();
    }
  }

private:
  static profile::ProductProfile load(const std::string& id, const Tweak& tweak, bool pinned) {
    profile::ProductProfile p = profile::load_profile(id);
    if (pinned) pin_gains(p);
    if (tweak) tweak(p);
    return p;
  }

  plant::PlantDescription description() const {
    plant::PlantDescription d = drive::default_plant(profile_);
    d.step_s = static_cast<double>(profile_.drive.control_period_ns) * 1e-9;
    return d;
  }

  AxisSample make_sample() const {
    AxisSample s;
    s.time = now_;
    s.dt_s = static_cast<double>(dt_) * 1e-9;
    s.position = position_user();
    s.velocity = velocity_user();
    s.torque = units_.torque_sign() * feedback().torque_nm / motor_.rated_torque_nm * 1000.0;
    s.position_demand = last_.position;
    s.velocity_demand = last_.velocity;
    s.torque_demand = last_.torque;
    return s;
  }

  profile::ProductProfile profile_;
  std::shared_ptr<const od::Dictionary> dictionary_;
  od::ObjectStore store_;
  UnitScaling units_;
  DriveContext ctx_;
  plant::Plant plant_;
  plant::MotorParams motor_;
  std::unique_ptr<ControlLoop> loop_;
  Nanos dt_ = 125'000;
  Nanos now_ = 0;
  AxisSample sample_;
  Setpoint last_;
};

}  // namespace vdrive::drive::test
