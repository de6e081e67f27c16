#pragma once
// The simulated causes of the alarms the drive supervises itself, checked every control step.
// Each cause raises the product's alarm named in profile.drive.alarms and stays
// "present" (blocking the clear) while it lasts:
//  - following error: |deviation| > profile.drive.levels.following_error while enabled (A6B 3014h
//    Pr0.14 -> Err24.0, DS5C1 P0-23 -> E-100 L7279, DS1000A-EC 2108h in pulses -> FF02h L4336-L4350);
//    a level of 0 turns the check off (ParameterRef: 0 reads the fallback);
//  - overspeed: |speed| > profile.drive.levels.overspeed_rpm, or overspeed_factor x 6080h where the
//    product has no level (A6B 3513h -> Err26.0, DS5C1 P3-21 -> E-080 L7274, DS1000A-EC FF03h), or the
//    plant reports overspeed;
//  - overtemperature: the plant reports winding overtemperature;
//  - overload: the plant reports a stepper that lost steps (DS1000A-EC loop error "overload / speed
//    not following", L4324-L4334); for servos an I^2 t load factor, (torque / rated)^2 filtered with
//    levels.overload_time_constant_s, beyond levels.overload (A6B Err16.0 at 3512h, DS5C1 E-161).
// Nothing here allocates after construction.
#include <cstdint>

#include "common/cached_exp.hpp"
#include "common/clock.hpp"
#include "vdrive/drive/alarms/alarm_manager.hpp"
#include "vdrive/drive/parameter_value.hpp"
#include "vdrive/drive/drive_context.hpp"

namespace vdrive::drive {

struct MonitorInputs {
  double following_error_user = 0.0;        // 60F4h before rounding
  double following_error_increments = 0.0;  // the same in encoder increments
  double following_error_revolutions = 0.0; // the same in motor revolutions
  double motor_speed_rpm = 0.0;
  double max_motor_speed_rpm = 0.0;         // 6080h in r/min
  double torque_ratio = 0.0;                // actual torque / rated torque
  double dt_s = 0.0;                        // time since the previous step
  std::uint32_t plant_faults = 0;           // plant::fault:: bits
  bool enabled = false;                     // Operation enabled in a position mode (the position loop runs)
  Nanos now = 0;
};

class AlarmMonitors {
public:
  AlarmMonitors(const DriveContext& ctx, AlarmManager& alarms);

  void step(const MonitorInputs& in);
  void power_on() { load_factor_ = 0.0; }   // a cold motor

  // The levels in force (for diagnostics and tests): following error in the level's own unit
  // (increments or user units), overspeed in r/min. 0 = not supervised.
  double following_error_level() const { return following_error_level_.get(); }
  double overspeed_level_rpm(double max_motor_speed_rpm) const;
  double load_factor() const { return load_factor_; }   // I^2 t state, 1.0 = rated torque continuous

private:
  void watch(const profile::AlarmSpec* alarm, bool cause, Nanos now);

  const DriveContext& ctx_;
  AlarmManager& alarms_;
  ParameterValue following_error_level_, overspeed_level_, overload_level_;
  double load_factor_ = 0.0;
  CachedExp overload_exp_;
  const profile::AlarmSpec* following_error_ = nullptr;
  const profile::AlarmSpec* overspeed_ = nullptr;
  const profile::AlarmSpec* overload_ = nullptr;
  const profile::AlarmSpec* overtemperature_ = nullptr;
};

}  // namespace vdrive::drive
