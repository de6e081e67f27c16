#include "vdrive/drive/pds/stop_sequence.hpp"

#include <algorithm>
#include <cmath>

#include "vdrive/drive/motion_ramp.hpp"

namespace vdrive::drive {

namespace {

// "如果设定为 0，内部处理作为 1 操作" (A6B L26360, L26388, L26400, L26412, L26428).
double at_least_one(std::uint32_t v) { return v == 0 ? 1.0 : static_cast<double>(v); }

bool velocity_mode(std::int8_t m) { return m == mode::pv || m == mode::csv || m == mode::vl; }

}  // namespace

StopSequence::StopSequence(const DriveContext& ctx)
    : ctx_(ctx),
      vendor_(ctx),
      profile_dec_(ctx.objects, 0x6084),
      quick_stop_dec_(ctx.objects, 0x6085),
      max_dec_(ctx.objects, 0x60C6),
      homing_acc_(ctx.objects, 0x609A),
      torque_slope_(ctx.objects, 0x6087) {}

double StopSequence::stopped_speed() const {
  return std::abs(ctx_.units.rpm_to_user(ctx_.profile.drive.stopped_speed_rpm));
}

bool StopSequence::stopped(double velocity) const { return std::abs(velocity) <= stopped_speed(); }

void StopSequence::start(StopKind kind, std::int8_t mode, const AxisSample& s, DriveSideAction drive_side) {
  kind_ = kind;
  action_ = DriveSideAction::None;
  ramping_ = false;
  position_setpoints_ = !velocity_mode(mode);
  rate_ = 0.0;
  torque_limit_ = 0.0;
  const bool torque = is_torque_mode(mode);
  switch (kind) {
    case StopKind::None:
      shape_ = Shape::Hold;
      break;
    case StopKind::Coast:
    case StopKind::ZeroTorque:
      shape_ = Shape::Free;
      break;
    case StopKind::SlowDown:
    case StopKind::QuickStopRamp:
    case StopKind::CurrentLimit:
      if (torque) {  // every ramp code of tq/cst is the torque slope (A6B L27051, L27183, L27564)
        shape_ = Shape::TorqueRamp;
        rate_ = at_least_one(torque_slope_.get());
      } else {
        shape_ = Shape::SpeedRamp;
        const ObjectRef<std::uint32_t>& ramp = kind == StopKind::QuickStopRamp ? quick_stop_dec_
                                               : kind == StopKind::CurrentLimit ? max_dec_
                                               : mode == mode::hm                ? homing_acc_  // L27031
                                                                                 : profile_dec_;
        rate_ = at_least_one(ramp.get());
      }
      break;
    case StopKind::DriveSide:
      action_ = drive_side == DriveSideAction::None ? vendor_.servo_off() : drive_side;
      switch (action_) {
        case DriveSideAction::Decelerate: {
          // Down from the present speed within P0-31 (DS5C1 L8682); no time given: at once.
          const double t = vendor_.decelerate_time_s();
          shape_ = Shape::SpeedRamp;
          rate_ = t > 0.0 ? std::max(std::abs(s.velocity_demand), std::abs(s.velocity)) / t : 0.0;
          if (rate_ <= 0.0) shape_ = Shape::Immediate;
          break;
        }
        case DriveSideAction::ImmediateStop:
          shape_ = Shape::Immediate;
          torque_limit_ = vendor_.immediate_stop_torque();
          break;
        default:
          shape_ = Shape::Free;
          break;
      }
      break;
  }
}

Setpoint StopSequence::step(const AxisSample& s) {
  Setpoint sp;
  switch (shape_) {
    case Shape::Hold:
      sp.kind = Setpoint::Kind::Position;
      sp.position = s.position_demand;
      break;
    case Shape::Free:  // no torque; demands follow the axis so a later enable starts where it is
      sp.kind = Setpoint::Kind::Torque;
      sp.position = s.position;
      sp.velocity = s.velocity;
      sp.torque = 0.0;
      break;
    case Shape::TorqueRamp: {
      const double dt_step = rate_ * s.dt_s;
      sp.kind = Setpoint::Kind::Torque;
      sp.position = s.position;
      sp.velocity = s.velocity;
      sp.torque = s.torque_demand - std::clamp(s.torque_demand, -dt_step, dt_step);
      break;
    }
    case Shape::SpeedRamp: {
      // With position set-points 606Bh (s.velocity_demand) is the mean speed of the last step,
      // half a step's deceleration above the ramp's own end speed: ramping from it every step ran
      // the stop at half the rate. Continue from the ramp's end speed while the axis took its last
      // set-point (the demand is where the ramp left it).
      MotionState from{s.position_demand, s.velocity_demand};
      if (position_setpoints_ && ramping_ && ramp_.position == s.position_demand) from.velocity = ramp_.velocity;
      const MotionState next = ramp_velocity(from, 0.0, rate_, rate_, s.dt_s);
      ramp_ = next;
      ramping_ = true;
      sp.kind = position_setpoints_ ? Setpoint::Kind::Position : Setpoint::Kind::Velocity;
      sp.position = next.position;
      sp.velocity = next.velocity;
      break;
    }
    case Shape::Immediate:
      sp.kind = Setpoint::Kind::Velocity;
      sp.position = s.position;
      sp.velocity = 0.0;
      sp.torque_limit = torque_limit_;
      break;
  }
  return sp;
}

}  // namespace vdrive::drive
