#pragma once
// A whole drive on the bench: a real product (profile, dictionary, values), its default plant
// (drive::default_plant) and a DriveEngine, with the EtherCAT side in Op. A "master" writes the
// RxPDO objects (6040h, 6060h, targets) once per bus cycle and tells the engine, as the
// process-data module does; tests read back the actual values and the physics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "plant/plant.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/drive/product_plant.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive::test {

inline constexpr Nanos kMs = 1'000'000;
inline constexpr std::uint16_t kCwShutdown = 0x0006, kCwSwitchOn = 0x0007, kCwEnable = 0x000F,
                               kCwFaultReset = 0x0080, kCwNewSetPoint = 0x0010, kCwHalt = 0x0100;

class EngineBench {
public:
  using Tweak = std::function<void(profile::ProductProfile&, plant::PlantDescription&)>;

  explicit EngineBench(const std::string& id, const Tweak& tweak = {})
      : profile_(profile::load_profile(id)), plant_description_(drive::default_plant(profile_)) {
    if (tweak) tweak(profile_, plant_description_);
    dictionary_ = od::shared_dictionary(profile_);
    store_ = std::make_unique<od::ObjectStore>(*dictionary_);
    plant_ = std::make_unique<plant::Plant>(plant_description_);
    engine_ = std::make_unique<DriveEngine>(profile_, *store_, *plant_, 0, plant_description_.axes.at(0),
                                            [this](const ecat::coe::Emergency& e) { emergencies.push_back(e); });
    engine_->power_on(0);
    to_op();
  }

  // The ESM walks Init -> PreOp -> SafeOp -> Op (units are latched on the way).
  void to_op() {
    using ecat::AlState;
    bus.esm_init = false;
    bus.remote = true;
    engine_->esm_changed(AlState::Init, AlState::PreOp, now_);
    engine_->esm_changed(AlState::PreOp, AlState::SafeOp, now_);
    engine_->esm_changed(AlState::SafeOp, AlState::Op, now_);
  }
  void leave_op(ecat::AlState to) {
    engine_->esm_changed(ecat::AlState::Op, to, now_);
    bus.esm_init = to == ecat::AlState::Init;
  }

  DriveEngine& engine() { return *engine_; }
  const profile::ProductProfile& profile() const { return profile_; }
  od::ObjectStore& store() { return *store_; }
  plant::Plant& plant() { return *plant_; }
  const plant::AxisFeedback& feedback() const { return plant_->feedback(0); }
  Nanos now() const { return now_; }

  bool has(std::uint16_t index, std::uint8_t sub = 0) const { return dictionary_->find(index, sub) != nullptr; }
  void set(std::uint16_t index, std::uint8_t sub, std::int64_t value) {
    ObjectRef<std::int64_t> ref(*store_, index, sub);
    ASSERT_TRUE(ref.present()) << std::hex << index << ":" << int(sub);
    ref.set(value);
  }
  std::int64_t get(std::uint16_t index, std::uint8_t sub = 0) const {
    return ObjectRef<std::int64_t>(*store_, index, sub).get();
  }
  std::uint16_t status() const { return static_cast<std::uint16_t>(get(0x6041)); }
  std::int32_t position() const { return static_cast<std::int32_t>(get(0x6064)); }
  std::int32_t velocity() const { return static_cast<std::int32_t>(get(0x606C)); }

  // For failure messages: statusword, 603Fh and the newest alarm.
  std::string diag() {
    const profile::AlarmSpec* a = engine_->alarms().newest();
    char buf[160];
    std::snprintf(buf, sizeof buf, "6041h=%04X 603Fh=%04X alarm=%s state=%d mode=%d", status(),
                  static_cast<unsigned>(get(0x603F)), a ? a->code.c_str() : "-", static_cast<int>(engine_->state()),
                  engine_->mode());
    return buf;
  }

  // User units per motor revolution in force.
  double per_rev() const { return 2.0 * std::numbers::pi / engine_->units().motor_rad_per_user(); }
  // User units/s for `rpm` motor speed.
  double user_speed(double rpm) const { return rpm / 60.0 * per_rev(); }
  double motor_rpm() const { return feedback().motor_velocity_rad_s * 60.0 / (2.0 * std::numbers::pi); }
  double motor_revs() const { return feedback().motor_angle_rad / (2.0 * std::numbers::pi); }

  // Runs for `duration` in bus cycles of `cycle`; `master(now)` writes the outputs at the start of
  // each cycle, then the engine takes them over (outputs_taken) and runs its control steps.
  void run(Nanos duration, const std::function<void(Nanos)>& master = {}, Nanos cycle = kMs) {
    const Nanos end = now_ + duration;
    while (now_ < end) {
      if (master) master(now_);
      engine_->advance_to(now_, bus);
      engine_->outputs_taken(now_);
      now_ += cycle;
      // The DC time the master gave moves on with the clock, as the ESC's does (0: none given).
      BusState later = bus;
      if (later.system_time_ns != 0) later.system_time_ns += static_cast<std::uint64_t>(cycle - 1);
      engine_->advance_to(now_ - 1, later);
    }
  }
  // Runs until `done()` or `limit`; true if done.
  bool run_until(const std::function<bool()>& done, Nanos limit, const std::function<void(Nanos)>& master = {}) {
    const Nanos end = now_ + limit;
    while (now_ < end) {
      run(kMs, master);
      if (done()) return true;
    }
    return false;
  }

  // Controlword for a few cycles.
  void command(std::uint16_t cw, Nanos duration = 5 * kMs) {
    set(0x6040, 0, cw);
    run(duration);
  }

  // Mode `m`, then 6 -> 7 -> 15 (the enable sequence of every manual); true when Operation enabled.
  bool enable(std::int8_t m) {
    set(0x6060, 0, m);
    command(kCwShutdown);
    command(kCwSwitchOn);
    command(kCwEnable, 20 * kMs);
    return engine_->state() == PdsState::OperationEnabled && engine_->mode() == m;
  }


  BusState bus{};
  std::vector<ecat::coe::Emergency> emergencies;

private:
  profile::ProductProfile profile_;
  plant::PlantDescription plant_description_;
  std::shared_ptr<const od::Dictionary> dictionary_;
  std::unique_ptr<od::ObjectStore> store_;
  std::unique_ptr<plant::Plant> plant_;
  std::unique_ptr<DriveEngine> engine_;
  Nanos now_ = 0;
};

}  // namespace vdrive::drive::test
