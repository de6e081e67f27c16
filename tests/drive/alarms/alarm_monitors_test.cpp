// The simulated alarm causes: following error, overspeed, overtemperature and overload raise the
// product's alarm (profile.drive.alarms) against the vendor levels (profile.drive.levels). The
// profiles are copies with the levels and codes set here, so the tests do not depend on profile.yaml.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "plant/plant.hpp"
#include "vdrive/drive/alarms/alarm_monitors.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::drive {
namespace {

using ecat::coe::Emergency;

profile::ProductProfile tweaked(std::string_view id, const std::function<void(profile::ProductProfile&)>& tweak) {
  profile::ProductProfile p = profile::load_profile(id);
  tweak(p);
  return p;
}

struct Bench {
  Bench(std::string_view id, const std::function<void(profile::ProductProfile&)>& tweak)
      : profile(tweaked(id, tweak)), dict(od::shared_dictionary(profile)), store(*dict), ctx{profile, store, units},
        alarms(ctx, [this](const Emergency& e) { emcy.push_back(e); }), monitors(ctx, alarms) {
    alarms.power_on();
  }
  profile::ProductProfile profile;
  std::shared_ptr<const od::Dictionary> dict;
  od::ObjectStore store;
  UnitScaling units;
  DriveContext ctx;
  std::vector<Emergency> emcy;
  AlarmManager alarms;
  AlarmMonitors monitors;
};

void a6b_levels(profile::ProductProfile& p) {
  p.drive.levels.following_error = {0x3014, 0, 1.0, 0.0};   // Pr0.14, command units (L34735)
  p.drive.levels.overspeed_rpm = {0x3513, 0, 1.0, 0.0};     // Pr5.13, r/min (L35920)
  p.drive.overspeed_factor = 1.2;
  p.drive.alarms.following_error = "24.0";
  p.drive.alarms.overspeed = "26.0";
  p.drive.alarms.overtemperature = "15.1";
  p.drive.alarms.overload = "";
}

MonitorInputs enabled_at(Nanos now) {
  MonitorInputs in;
  in.enabled = true;
  in.now = now;
  in.max_motor_speed_rpm = 5000.0;
  return in;
}

TEST(AlarmMonitors, FollowingErrorBeyondTheLevelRaisesErr24_0AndBlocksTheClearWhileItLasts) {
  Bench b("a6b", a6b_levels);
  ObjectRef<std::int32_t>(b.store, 0x3014).set(1000);
  EXPECT_DOUBLE_EQ(b.monitors.following_error_level(), 1000.0);
  MonitorInputs in = enabled_at(0);
  in.following_error_user = 1000.0;   // at the level: not beyond it
  b.monitors.step(in);
  EXPECT_FALSE(b.alarms.active());
  in.following_error_user = -1000.5;
  in.now = 1;
  b.monitors.step(in);
  ASSERT_TRUE(b.alarms.active());
  EXPECT_EQ(b.alarms.error_code(), 0xFF18);
  ASSERT_EQ(b.emcy.size(), 1u);
  EXPECT_EQ(b.emcy[0].error_code, 0xFF18);
  EXPECT_FALSE(b.alarms.reset(false, 2));   // cause still present
  in.enabled = false;                        // the drive disabled: the deviation no longer counts
  in.following_error_user = 0.0;
  b.monitors.step(in);
  EXPECT_TRUE(b.alarms.reset(false, 3));
  EXPECT_FALSE(b.alarms.active());
}

TEST(AlarmMonitors, FollowingErrorIsNotCheckedWhileDisabledOrWithLevelZero) {
  Bench b("a6b", a6b_levels);
  ObjectRef<std::int32_t>(b.store, 0x3014).set(0);   // factory 100000 (od-overrides.yaml): set the 0 assumed here
  MonitorInputs in = enabled_at(0);
  in.following_error_user = 1e9;   // 3014h = 0: no level, no check
  b.monitors.step(in);
  EXPECT_FALSE(b.alarms.active());
  ObjectRef<std::int32_t>(b.store, 0x3014).set(10);
  in.enabled = false;
  b.monitors.step(in);
  EXPECT_FALSE(b.alarms.active());
}

TEST(AlarmMonitors, OverspeedUsesPr5_13OrTheFactorTimes6080h) {
  Bench b("a6b", a6b_levels);
  // 3513h = 0: 1.2 x 5000 r/min = 6000 r/min.
  EXPECT_DOUBLE_EQ(b.monitors.overspeed_level_rpm(5000.0), 6000.0);
  MonitorInputs in = enabled_at(0);
  in.motor_speed_rpm = -5999.0;
  b.monitors.step(in);
  EXPECT_FALSE(b.alarms.active());
  ObjectRef<std::int16_t>(b.store, 0x3513).set(4000);
  in.motor_speed_rpm = -4001.0;
  in.enabled = false;   // overspeed is watched whether enabled or not
  b.monitors.step(in);
  ASSERT_TRUE(b.alarms.active());
  EXPECT_EQ(b.alarms.error_code(), 0xFF1A);   // Err26 -> 1Ah
}

TEST(AlarmMonitors, PlantFaultsRaiseOvertemperatureAndOverload) {
  Bench b("a6b", a6b_levels);
  MonitorInputs in = enabled_at(0);
  in.plant_faults = plant::fault::overtemperature;
  b.monitors.step(in);
  ASSERT_TRUE(b.alarms.active());
  EXPECT_EQ(b.alarms.error_code(), 0xFF0F);   // Err15.1 -> 0Fh
  EXPECT_FALSE(b.alarms.reset(false, 1));
  in.plant_faults = plant::fault::overspeed;
  b.monitors.step(in);
  EXPECT_EQ(b.alarms.error_code(), 0xFF1A);

  Bench s("ds1000a", [](profile::ProductProfile& p) { p.drive.alarms.overload = "FF01h"; });
  MonitorInputs lost = enabled_at(0);
  lost.plant_faults = plant::fault::lost_steps;   // loop error: speed not following (L4324-L4334)
  s.monitors.step(lost);
  EXPECT_EQ(s.alarms.error_code(), 0xFF01);
}

TEST(AlarmMonitors, Ds1000aFullCountLevelIsInPulses) {
  Bench b("ds1000a", [](profile::ProductProfile& p) {
    p.drive.levels.following_error = {0x2108, 0, 1.0, 0.0};   // 2108h FullCountValue, pulses (L4336-L4350)
    p.drive.levels.following_error_in_increments = true;
    p.drive.alarms.following_error = "FF02h";
  });
  ObjectRef<std::int32_t>(b.store, 0x2108).set(4000);
  MonitorInputs in = enabled_at(0);
  in.following_error_user = 1e6;             // user units are not what 2108h counts
  in.following_error_increments = 3999.0;
  b.monitors.step(in);
  EXPECT_FALSE(b.alarms.active());
  in.following_error_increments = 4001.0;
  b.monitors.step(in);
  EXPECT_EQ(b.alarms.error_code(), 0xFF02);
}

TEST(AlarmMonitors, CausesWithoutAnAlarmCodeRaiseNothing) {
  Bench b("a6b", [](profile::ProductProfile& p) {
    p.drive.alarms = {};
    p.drive.alarms.overspeed = "no such code";
  });
  MonitorInputs in = enabled_at(0);
  in.motor_speed_rpm = 1e6;
  in.plant_faults = plant::fault::overtemperature | plant::fault::lost_steps;
  b.monitors.step(in);
  EXPECT_FALSE(b.alarms.active());
}

}  // namespace
}  // namespace vdrive::drive
