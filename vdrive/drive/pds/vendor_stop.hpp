#pragma once
// The vendor's own ("servo-side") stops behind option code 0 and behind every alarm that 605Eh does
// not govern: what DriveSideAction a StopKind::DriveSide stop is, read from the product's sequence
// parameters when the stop starts. The product's drive.vendor_stop names the rule and the
// parameters it reads; the rules as the manuals give them:
//   A6B (panasonic):   3506h Sequence at Servo-Off (0-9), 3510h Sequence at alarm (0-7), 3511h emergency-stop
//          torque (L26447-L26467, L27701-L27711); 3510h 4-7 make the "immediate stop" alarms stop at
//          once (L32910). The meaning of each value is in the basic-function spec SX-DSV03243 (not
//          among the seeds): even = dynamic brake, odd = free run while stopping; 3506h 8/9 and
//          3510h 4-7 immediate stop.
//   DS5C1 (xinje): P0-27 servo-OFF stop (201Bh), P0-29 alarm stop (201Dh), P0-31 deceleration stop time
//          (201Fh, ms): 0/1 coast, 2/3 decelerate, 4/5 dynamic brake (L2166-L2240, L8677-L8682);
//          alarms with the servo-off attribute always coast (L2214-L2226).
//   DS1000A-EC (none): no sequence (code 0 is CiA 402 "disable drive function": Coast).
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/drive/pds/stop_kind.hpp"

namespace vdrive::drive {

class VendorStop {
public:
  explicit VendorStop(const DriveContext& ctx);

  bool present() const { return rule_ != Rule::None; }
  // Shutdown / Disable voltage / Disable operation / Quick stop with option code 0, main power off.
  DriveSideAction servo_off() const;
  // An alarm stopping by the vendor's sequence; `reaction` is the alarm's own (profile alarms.yaml).
  DriveSideAction alarm(profile::AlarmReaction reaction) const;
  // Torque limit of an ImmediateStop, 0.1 % of rated; 0 = the normal torque limit (A6B 3511h = 0).
  double immediate_stop_torque() const;
  // Time a Decelerate stop takes from the speed it starts at (DS5C1 P0-31), s.
  double decelerate_time_s() const;

private:
  using Rule = profile::VendorStopRule;
  Rule rule_ = Rule::None;
  ObjectRef<std::int16_t> servo_off_, alarm_, stop_torque_, stop_time_;
};

}  // namespace vdrive::drive
