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

}  // namespace

VendorStop::VendorStop(const DriveContext& ctx) {
  // The product decides which parameters exist; its id picks how their values read.
  if (ctx.profile.id == "a6b") {
    rule_ = Rule::Panasonic;
    servo_off_ = ObjectRef<std::int16_t>(ctx.objects, 0x3506);
    alarm_ = ObjectRef<std::int16_t>(ctx.objects, 0x3510);
    stop_torque_ = ObjectRef<std::int16_t>(ctx.objects, 0x3511);
  } else if (ctx.profile.id == "ds5c1") {
    rule_ = Rule::Xinje;
    servo_off_ = ObjectRef<std::int16_t>(ctx.objects, 0x201B);           // P0-27, default 0 (L2170)
    alarm_ = ObjectRef<std::int16_t>(ctx.objects, 0x201D, 0, 2);         // P0-29, default 2 (L2171)
    stop_time_ = ObjectRef<std::int16_t>(ctx.objects, 0x201F, 0, 25);    // P0-31, 25 ms (L8682)
  }
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
