#include "vdrive/drive/alarms/alarm_monitors.hpp"

#include <cmath>

#include "plant/plant.hpp"

namespace vdrive::drive {

AlarmMonitors::AlarmMonitors(const DriveContext& ctx, AlarmManager& alarms)
    : ctx_(ctx), alarms_(alarms), following_error_level_(ctx.objects, ctx.profile.drive.levels.following_error),
      overspeed_level_(ctx.objects, ctx.profile.drive.levels.overspeed_rpm),
      overload_level_(ctx.objects, ctx.profile.drive.levels.overload) {
  const profile::DriveAlarmCauses& causes = ctx.profile.drive.alarms;
  // "" or a code missing from the table: the product has no alarm for it (nullptr, never raised).
  following_error_ = causes.following_error.empty() ? nullptr : alarms.find(causes.following_error);
  overspeed_ = causes.overspeed.empty() ? nullptr : alarms.find(causes.overspeed);
  overload_ = causes.overload.empty() ? nullptr : alarms.find(causes.overload);
  overtemperature_ = causes.overtemperature.empty() ? nullptr : alarms.find(causes.overtemperature);
}

double AlarmMonitors::overspeed_level_rpm(double max_motor_speed_rpm) const {
  const double level = overspeed_level_.get();
  if (level > 0.0) return level;
  return ctx_.profile.drive.overspeed_factor * max_motor_speed_rpm;
}

void AlarmMonitors::step(const MonitorInputs& in) {
  const double fe_level = following_error_level_.get();
  const profile::DriveLevelSpec& levels = ctx_.profile.drive.levels;
  const double fe = levels.following_error_in_increments    ? in.following_error_increments
                    : levels.following_error_in_revolutions ? in.following_error_revolutions
                                                            : in.following_error_user;
  watch(following_error_, in.enabled && fe_level > 0.0 && std::abs(fe) > fe_level, in.now);

  const double os_level = overspeed_level_rpm(in.max_motor_speed_rpm);
  const bool too_fast = os_level > 0.0 && std::abs(in.motor_speed_rpm) > os_level;
  watch(overspeed_, too_fast || (in.plant_faults & plant::fault::overspeed) != 0, in.now);

  watch(overtemperature_, (in.plant_faults & plant::fault::overtemperature) != 0, in.now);

  const double tau = levels.overload_time_constant_s;
  if (tau > 0.0 && in.dt_s > 0.0)
    load_factor_ += (in.torque_ratio * in.torque_ratio - load_factor_) * (1.0 - overload_exp_(-in.dt_s / tau));
  const double overload_level = overload_level_.get();
  const bool overloaded = overload_level > 0.0 && load_factor_ > overload_level;
  watch(overload_, overloaded || (in.plant_faults & plant::fault::lost_steps) != 0, in.now);
}

void AlarmMonitors::watch(const profile::AlarmSpec* alarm, bool cause, Nanos now) {
  if (!alarm) return;
  alarms_.set_cause(*alarm, cause);
  if (cause) alarms_.raise(*alarm, now);   // no-op while it is active
}

}  // namespace vdrive::drive
