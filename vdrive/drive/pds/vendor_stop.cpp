#include "vdrive/drive/pds/vendor_stop.hpp"

namespace vdrive::drive {

namespace {

// A6B 3506h / 3510h 0-3 (and 4-7 after the immediate stop): even values dynamic brake, odd free
// run while decelerating (Pr5.06/Pr5.10 of SX-DSV03243; the seed names the three servo-side
// stops only, L26288-L26290).
DriveSideAction panasonic_braking(std::int16_t v) {
  return (v & 1) ? DriveSideAction::FreeRun : DriveSideAction::DynamicBrake;
}

// DS5C1 P0-27 / P0-29 (L2173-L2194).
DriveSideAction xinje(std::int16_t v) {
  if (v == 2 || v == 3) return DriveSideAction::Decelerate;
  if (v == 4 || v == 5) return DriveSideAction::DynamicBrake;
  return DriveSideAction::FreeRun;  // 0, 1 (and anything else: the servo lets go)
}

// Index 0 names no object, so the handle reads the fallback.
ObjectRef<std::int16_t> slot(od::ObjectStore& objects, const profile::ObjectSlot& s) {
  return ObjectRef<std::int16_t>(objects, s.index, s.subindex, s.fallback);
}

}  // namespace

VendorStop::VendorStop(const DriveContext& ctx) {
  // The product names the parameters and how their values read (drive.vendor_stop).
  const profile::VendorStopSpec& spec = ctx.profile.drive.vendor_stop;
  rule_ = spec.rule;
  servo_off_ = slot(ctx.objects, spec.servo_off);
  alarm_ = slot(ctx.objects, spec.alarm);
  stop_torque_ = slot(ctx.objects, spec.stop_torque);
  stop_time_ = slot(ctx.objects, spec.stop_time_ms);
}

DriveSideAction VendorStop::servo_off() const {
  const std::int16_t v = servo_off_.get();
  switch (rule_) {
    case Rule::Panasonic: return (v == 8 || v == 9) ? DriveSideAction::ImmediateStop : panasonic_braking(v);
    case Rule::Xinje: return xinje(v);
    case Rule::None: break;
  }
  return DriveSideAction::FreeRun;
}

DriveSideAction VendorStop::alarm(profile::AlarmReaction reaction) const {
  const std::int16_t v = alarm_.get();
  switch (rule_) {
    case Rule::Panasonic:
      // Only the alarms whose "immediate stop" column says Yes stop at once, and only with
      // 3510h = 4-7 (L32910); the rest brake or run free as 3510h says.
      if (v >= 4 && v <= 7 && reaction == profile::AlarmReaction::ImmediateStop) return DriveSideAction::ImmediateStop;
      return panasonic_braking(v);
    case Rule::Xinje:
      // Alarms that switch the servo off coast whatever P0-29 says (L2214-L2226).
      if (reaction == profile::AlarmReaction::FreeRun) return DriveSideAction::FreeRun;
      return xinje(v);
    case Rule::None: break;
  }
  return DriveSideAction::FreeRun;
}

double VendorStop::immediate_stop_torque() const {
  return 10.0 * static_cast<double>(stop_torque_.get());  // 3511h is in %, 0 = normal limit (L27709-L27711)
}

double VendorStop::decelerate_time_s() const {
  const std::int16_t ms = stop_time_.get();
  return ms > 0 ? ms / 1000.0 : 0.0;
}

}  // namespace vdrive::drive
