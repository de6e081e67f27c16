#include "vdrive/drive/modes/homing_mode.hpp"

#include <algorithm>
#include <cmath>

namespace vdrive::drive {

namespace {

constexpr Nanos ms(std::int64_t v) { return static_cast<Nanos>(v) * 1'000'000; }
constexpr double kMaxSpeed = 2147483647.0;  // 6099h limit besides 6080h (A6B L17940-L17950)
constexpr Nanos kAttainedPulse = ms(2);     // 35/37: bit 12 low for about 2 ms (A6B L18211-L18212)

std::uint32_t mask(HomingSwitch sw) {
  switch (sw) {
    case HomingSwitch::NegativeLimit: return din::negative_limit;
    case HomingSwitch::PositiveLimit: return din::positive_limit;
    case HomingSwitch::Home: return din::home;
    default: return 0;
  }
}

bool is_active(HomingSwitch sw, std::uint32_t inputs) { return sw != HomingSwitch::None && (inputs & mask(sw)); }

int sign(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }

}  // namespace

HomingMode::HomingMode(const DriveContext& ctx)
    : ctx_(ctx), rules_(ctx.profile.homing), method_(ctx.objects, 0x6098),
      speed_switch_(ctx.objects, 0x6099, 1), speed_zero_(ctx.objects, 0x6099, 2),
      acceleration_(ctx.objects, 0x609A), max_motor_speed_(ctx.objects, 0x6080),
      quick_stop_dec_(ctx.objects, 0x6085), home_offset_(ctx.objects, 0x607C),
      halt_option_(ctx.objects, 0x605D, 0, 1), positive_torque_(ctx.objects, 0x60E0, 0, 65535),
      negative_torque_(ctx.objects, 0x60E1, 0, 65535),
      // DS5C1 P9-16 (2 r/min), P9-17 (100 %), P9-18 (500 ms), P9-19/P9-20, P7-20 (1): L8966, L8984-L8988.
      stop_speed_rpm_(ctx.objects, 0x2910, 0, 2), stop_torque_pct_(ctx.objects, 0x2911, 0, 100),
      stop_time_ms_(ctx.objects, 0x2912, 0, 500), fixed_low_(ctx.objects, 0x2913), fixed_high_(ctx.objects, 0x2914),
      z_count_(ctx.objects, 0x2714, 0, 1), torque_detect_ms_(ctx.objects, 0x2142, 0, 100) {}

// --- ModeHandler -----------------------------------------------------------------------------------

void HomingMode::activate(const AxisSample& s) {
  cmd_ = {s.position_demand, s.velocity_demand};
  // A mode switch ends any run; bit 4 already 1 does not start one (A6B L17736-L17764: only 0->1).
  if (phase_ != Phase::Idle && phase_ != Phase::Pulse) outcome_ = Outcome::Interrupted;
  if (phase_ != Phase::Pulse) phase_ = Phase::Idle;
  prev_start_ = true;
}

void HomingMode::idle(const AxisSample& s, std::uint16_t controlword) {
  cmd_ = {s.position, 0.0};
  frame_shift_ = 0.0;
  const bool bit4 = controlword & cw::new_set_point;
  const bool edge = bit4 && !prev_start_;
  prev_start_ = bit4;
  if (phase_ == Phase::Settle) {  // home was found and preset; the stop sequence ends the run
    phase_ = Phase::Idle;
    outcome_ = Outcome::Completed;
  } else if (phase_ == Phase::Stopping) {
    phase_ = Phase::Idle;
    outcome_ = stop_outcome_;
  } else if (running()) {  // power removed or a stop sequence: the run is interrupted
    phase_ = Phase::Idle;
    outcome_ = Outcome::Interrupted;
  }
  if (edge && phase_ == Phase::Idle) start(s, /*enabled=*/false);
  if (phase_ == Phase::Pulse) finish_pulse(s);
}

Setpoint HomingMode::step(const AxisSample& s, std::uint16_t controlword) {
  cmd_.position += frame_shift_;
  frame_shift_ = 0.0;
  const bool bit4 = controlword & cw::new_set_point;
  const bool edge = bit4 && !prev_start_;
  prev_start_ = bit4;
  if (edge && (phase_ == Phase::Idle || phase_ == Phase::Pulse)) start(s, /*enabled=*/true);

  const bool halted = controlword & cw::halt;
  if (halted && running() && phase_ != Phase::Stopping) {
    if (ctx_.profile.drive.halt_aborts_homing) {
      // Cancelling once home was detected loses the position information (A6B Err27.7).
      if (phase_ == Phase::Settle || phase_ == Phase::FixedMove || phase_ == Phase::PushIndex)
        alarm_ = rules_.cancel_after_detection_alarm;
      stop(phase_ == Phase::Settle ? Outcome::Completed : Outcome::Interrupted, halt_deceleration());
    } else {
      const Setpoint sp = run(s, 0.0);  // pause: stand, take the leg up again on release
      return sp;
    }
  }

  switch (phase_) {
    case Phase::Seek: return step_seek(s);
    case Phase::Brake: return step_brake(s);
    case Phase::Approach: return step_approach(s);
    case Phase::IndexSearch: return step_index(s);
    case Phase::Push: return step_push(s);
    case Phase::PushIndex: return step_push_index(s);
    case Phase::FixedMove: return step_fixed_move(s);
    case Phase::Settle:
      if (s.stopped) {
        phase_ = Phase::Idle;
        outcome_ = Outcome::Completed;
      }
      return hold();
    case Phase::Stopping: {
      if (stop_decel_ > 0.0)
        cmd_ = ramp_velocity(cmd_, 0.0, stop_decel_, stop_decel_, s.dt_s);
      else
        cmd_.velocity = 0.0;
      if (cmd_.velocity == 0.0 && s.stopped) {
        phase_ = Phase::Idle;
        outcome_ = stop_outcome_;
      }
      if (cmd_.velocity == 0.0) return hold();
      return {Setpoint::Kind::Velocity, cmd_.position, cmd_.velocity};
    }
    case Phase::Pulse: finish_pulse(s); return hold();
    case Phase::Idle: break;
  }
  cmd_.velocity = 0.0;
  return hold();
}

std::uint16_t HomingMode::status_bits() const {
  std::uint16_t bits = 0;
  if (attained_) bits |= sw::oms12;
  if (error_) bits |= sw::oms13;
  switch (phase_) {
    case Phase::Idle:
    case Phase::Pulse: bits |= sw::target_reached; break;
    default: break;  // moving: 000, 010 (Settle) or 100 (Stopping after an error)
  }
  return bits;
}

bool HomingMode::take_home_found(double& position) {
  if (!home_pending_) return false;
  home_pending_ = false;
  position = home_position_;
  return true;
}

std::string_view HomingMode::pending_alarm() {
  const std::string_view a = alarm_;
  alarm_ = {};
  return a;
}

// --- Start and end of a run ------------------------------------------------------------------------

bool HomingMode::start_error(const AxisSample& s, bool enabled) const {
  const std::int8_t m = method_.get();
  const auto& listed = ctx_.profile.homing.methods;
  // A method the product does not list (A6B L17872-L17876, DS1000A-EC L2762-L2764).
  if (m == 0 || std::find(listed.begin(), listed.end(), m) == listed.end()) return true;
  if (spec_ == nullptr && hard_ == nullptr) return true;  // A6B -1..-4: manufacturer use only
  if (spec_ != nullptr && spec_->kind == HomingKind::CurrentPosition) return false;
  if (!enabled) return true;  // A6B L18659, DS5C1 L3525
  // 6099h = 0 (A6B L18663-L18665, DS5C1 L3526): 33/34 use one speed only.
  if (spec_ != nullptr && spec_->kind == HomingKind::IndexOnly) {
    if ((rules_.index_methods_use_switch_speed ? v_switch_ : v_zero_) <= 0.0) return true;
  } else if (v_switch_ <= 0.0 || v_zero_ <= 0.0) {
    return true;
  }
  // Both limits at the start (A6B L18668-L18669).
  return (s.inputs & din::negative_limit) && (s.inputs & din::positive_limit);
}

void HomingMode::start(const AxisSample& s, bool enabled) {
  const std::int8_t m = method_.get();
  spec_ = find_standard_homing_method(m);
  hard_ = spec_ ? nullptr : find_hard_stop(rules_, m);
  double vmax = kMaxSpeed;
  if (max_motor_speed_.present() && max_motor_speed_.get() > 0)
    vmax = std::min(vmax, ctx_.units.rpm_to_user(static_cast<double>(max_motor_speed_.get())));
  v_switch_ = std::min(static_cast<double>(speed_switch_.get()), vmax);
  v_zero_ = std::min(static_cast<double>(speed_zero_.get()), vmax);
  acc_ = std::max<double>(1.0, static_cast<double>(acceleration_.get()));  // 0 -> 1 (A6B L17982)
  const bool current_position = spec_ && spec_->kind == HomingKind::CurrentPosition;
  reference_value_ = (rules_.offset_only_for_current_position && !current_position)
                         ? 0.0
                         : static_cast<double>(home_offset_.get());
  error_ = false;
  attained_ = false;  // cleared at every start (A6B L18209)
  alarm_ = {};
  home_pending_ = false;
  push_timer_.reset();
  watch_ = exempt_limit_ = HomingSwitch::None;

  if (start_error(s, enabled)) {
    error_ = true;
    phase_ = Phase::Idle;
    outcome_ = Outcome::Error;
    return;
  }
  outcome_ = Outcome::NotStarted;
  if (current_position) {
    found(s, s.position);
    attained_ = false;
    phase_ = Phase::Pulse;
    pulse_end_ = s.time + kAttainedPulse;
    return;
  }
  if (hard_ != nullptr) {
    const bool xinje = rules_.vendor_methods == profile::HomingVendorMethods::XinjeHardStop;
    if (xinje) {
      push_limit_ = 10.0 * static_cast<double>(std::max(0, stop_torque_pct_.get()));  // % -> 0.1 %
    } else {  // the torque limit in force in the push direction, at most 100 % (L3874-L3878)
      const double lim = hard_->direction > 0 ? positive_torque_.get() : negative_torque_.get();
      push_limit_ = std::min(lim, 1000.0);
    }
    begin_leg({Phase::Push, hard_->direction, hard_->push_at_zero_speed ? v_zero_ : v_switch_});
    return;
  }
  if (spec_->kind == HomingKind::IndexOnly) {
    edge_position_ = s.position;
    begin_leg({Phase::IndexSearch, spec_->final_direction,
               rules_.index_methods_use_switch_speed ? v_switch_ : v_zero_});
    return;
  }
  // Where the axis is relative to the reference switch.
  if (reference_active(s.inputs))
    where_ = Region::Inside;
  else if (spec_->shape == SwitchShape::ActiveBelow)
    where_ = Region::Above;
  else if (spec_->shape == SwitchShape::ActiveAbove)
    where_ = Region::Below;
  else
    where_ = Region::Unknown;
  plan_next();
}

void HomingMode::fail(const AxisSample& s) {
  (void)s;
  error_ = true;
  attained_ = false;
  stop(Outcome::Error, rules_.abrupt_sensor_stop ? 0.0 : acc_);
}

void HomingMode::stop(Outcome outcome, double deceleration) {
  phase_ = Phase::Stopping;
  stop_outcome_ = outcome;
  stop_decel_ = deceleration;
}

void HomingMode::found(const AxisSample& s, double reference_point) {
  (void)s;
  // The engine makes `home_position_` read 607Ch (its value now); the reference point must read
  // reference_value_ (607Ch as latched at the start, or 0), so hand over the point that does.
  const double offset_now = static_cast<double>(home_offset_.get());
  home_position_ = reference_point + offset_now - reference_value_;
  home_pending_ = true;
  attained_ = true;
  phase_ = Phase::Settle;
  cmd_.velocity = 0.0;  // servo lock where the command is (A6B L17980)
  // From the next step on, the command lives in the re-referenced frame: new = old - position + 607Ch.
  next_ = {};
  frame_shift_ = offset_now - home_position_;
}

double HomingMode::halt_deceleration() const {
  switch (halt_option_.get()) {  // 605Dh: 1 homing ramp, 2 quick-stop ramp, 3 at once (A6B L27410-L27442)
    case 2: return std::max<double>(1.0, static_cast<double>(quick_stop_dec_.get()));
    case 3: return 0.0;
    default: return acc_;
  }
}

// --- Switch methods: legs ---------------------------------------------------------------------------

bool HomingMode::reference_active(std::uint32_t inputs) const { return is_active(spec_->reference, inputs); }

// The side of the reference edge from which the final approach starts.
HomingMode::Region HomingMode::pre_edge_region() const {
  if (spec_->upper_edge) return spec_->final_direction > 0 ? Region::Inside : Region::Above;
  return spec_->final_direction > 0 ? Region::Below : Region::Inside;
}

void HomingMode::plan_next() {
  const Region pre = pre_edge_region();
  if (where_ == pre) {
    begin_leg({Phase::Approach, spec_->final_direction, v_zero_});
  } else if (where_ == Region::Inside) {
    begin_leg({Phase::Seek, pre == Region::Below ? -1 : +1, v_switch_});
  } else if (where_ == Region::Below) {
    begin_leg({Phase::Seek, +1, v_switch_});
  } else if (where_ == Region::Above) {
    begin_leg({Phase::Seek, -1, v_switch_});
  } else {
    begin_leg({Phase::Seek, spec_->initial_direction, v_switch_});
  }
}

// Starts `leg`, braking first when the axis moves the other way. While braking, `watch` must keep
// `watch_state` (a switch flipping back means the deceleration overran it: homing error).
void HomingMode::begin_leg(Leg leg, HomingSwitch watch, bool watch_state) {
  leg_ = leg;
  exempt_limit_ = HomingSwitch::None;
  if (cmd_.velocity * leg.direction < 0.0) {
    next_ = leg;
    phase_ = Phase::Brake;
    watch_ = watch;
    watch_state_ = watch_state;
    if (rules_.abrupt_sensor_stop) cmd_.velocity = 0.0;
    return;
  }
  phase_ = leg.phase;
  watch_ = HomingSwitch::None;
}

// A limit switch is active in the direction of travel and the leg does not expect it
// (A6B L18668-L18716: limits during the switch or index search, except where the method reverses).
bool HomingMode::runs_into_limit(const AxisSample& s, int direction) const {
  for (const HomingSwitch lim : {HomingSwitch::NegativeLimit, HomingSwitch::PositiveLimit}) {
    if (!is_active(lim, s.inputs)) continue;
    const int toward = lim == HomingSwitch::NegativeLimit ? -1 : +1;
    if (direction != toward) continue;
    if (spec_ != nullptr && lim == spec_->reference) continue;
    if (lim == exempt_limit_) continue;
    if (phase_ == Phase::Seek && spec_ != nullptr && lim == spec_->reversal_limit) continue;
    return true;
  }
  return false;
}

Setpoint HomingMode::run(const AxisSample& s, double velocity, double torque_limit) {
  cmd_.position = s.position_demand;
  cmd_ = ramp_velocity(cmd_, velocity, acc_, acc_, s.dt_s);
  Setpoint sp{Setpoint::Kind::Velocity, cmd_.position, cmd_.velocity};
  sp.torque_limit = torque_limit;
  return sp;
}

Setpoint HomingMode::hold() const { return {Setpoint::Kind::Position, cmd_.position, 0.0}; }

Setpoint HomingMode::step_seek(const AxisSample& s) {
  if ((s.inputs & din::negative_limit) && (s.inputs & din::positive_limit)) {
    fail(s);  // both limits during homing (A6B L18668-L18669)
    return run(s, cmd_.velocity);
  }
  if (spec_->reversal_limit != HomingSwitch::None && is_active(spec_->reversal_limit, s.inputs) &&
      leg_.direction == (spec_->reversal_limit == HomingSwitch::PositiveLimit ? 1 : -1) &&
      where_ != Region::Inside) {
    // Outside the window on the far side: turn round at the limit; it must stay active while the
    // axis decelerates (A6B L18671-L18674).
    where_ = leg_.direction > 0 ? Region::Above : Region::Below;
    const Setpoint sp = run(s, cmd_.velocity);
    begin_leg({Phase::Seek, -leg_.direction, v_switch_}, spec_->reversal_limit, true);
    exempt_limit_ = spec_->reversal_limit;
    return sp;
  }
  if (runs_into_limit(s, leg_.direction)) {
    fail(s);
    return run(s, cmd_.velocity);
  }
  const bool active = reference_active(s.inputs);
  const bool reached = where_ == Region::Inside ? !active : active;
  if (!reached) return run(s, leg_.direction * leg_.speed);
  where_ = where_ == Region::Inside ? (leg_.direction > 0 ? Region::Above : Region::Below) : Region::Inside;
  const Setpoint sp = run(s, cmd_.velocity);
  plan_next();
  if (phase_ == Phase::Brake) {  // reversing on this edge: the switch must not flip back meanwhile
    watch_ = spec_->reference;
    watch_state_ = active;
  }
  return sp;
}

Setpoint HomingMode::step_brake(const AxisSample& s) {
  if (watch_ != HomingSwitch::None && is_active(watch_, s.inputs) != watch_state_) {
    fail(s);  // the switch was overrun during the reversal deceleration (A6B L18671-L18680)
    return run(s, cmd_.velocity);
  }
  if (runs_into_limit(s, sign(cmd_.velocity))) {
    fail(s);  // a limit during the reversal after the home switch (A6B L18681-L18685)
    return run(s, cmd_.velocity);
  }
  if (rules_.abrupt_sensor_stop) {
    cmd_.velocity = 0.0;
  } else {
    cmd_.position = s.position_demand;
    cmd_ = ramp_velocity(cmd_, 0.0, acc_, acc_, s.dt_s);
  }
  if (cmd_.velocity == 0.0) {
    phase_ = next_.phase;
    leg_ = next_;
    watch_ = HomingSwitch::None;
    exempt_limit_ = HomingSwitch::None;
    return hold();
  }
  return {Setpoint::Kind::Velocity, cmd_.position, cmd_.velocity};
}

Setpoint HomingMode::step_approach(const AxisSample& s) {
  if (((s.inputs & din::negative_limit) && (s.inputs & din::positive_limit)) ||
      runs_into_limit(s, leg_.direction)) {
    fail(s);
    return run(s, cmd_.velocity);
  }
  const bool active = reference_active(s.inputs);
  const bool crossed = where_ == Region::Inside ? !active : active;
  if (!crossed) return run(s, leg_.direction * leg_.speed);
  edge_position_ = s.position;
  if (spec_->index) {
    phase_ = Phase::IndexSearch;
    return run(s, leg_.direction * leg_.speed);
  }
  cmd_.position = s.position_demand;
  found(s, edge_position_);
  return hold();
}

Setpoint HomingMode::step_index(const AxisSample& s) {
  if (((s.inputs & din::negative_limit) && (s.inputs & din::positive_limit)) ||
      runs_into_limit(s, leg_.direction)) {
    fail(s);  // a limit during the index search (A6B L18686-L18694)
    return run(s, cmd_.velocity);
  }
  if (s.index_passed && (s.index_position - edge_position_) * leg_.direction >= 0.0) {
    cmd_.position = s.position_demand;
    found(s, s.index_position);
    return hold();
  }
  return run(s, leg_.direction * leg_.speed);
}

// --- Vendor hard-stop methods ----------------------------------------------------------------------

Setpoint HomingMode::step_push(const AxisSample& s) {
  const Setpoint sp = run(s, leg_.direction * leg_.speed, push_limit_);
  bool pressing = std::abs(s.torque) >= push_limit_ * 0.98;
  Nanos hold_for = ms(torque_detect_ms_.get());  // DS1000A-EC 2142h
  if (rules_.vendor_methods == profile::HomingVendorMethods::XinjeHardStop) {
    // |torque| at P9-17 and |speed| below P9-16 for P9-18 ms (L3551).
    const double still = ctx_.units.rpm_to_user(static_cast<double>(std::max(0, stop_speed_rpm_.get())));
    pressing = pressing && std::abs(s.velocity) < still;
    hold_for = ms(std::max(0, stop_time_ms_.get()));
  }
  if (!push_timer_.update(pressing, s.time, hold_for)) return sp;
  after_push(s, s.position);
  return hold();
}

void HomingMode::after_push(const AxisSample& s, double stop_position) {
  cmd_ = {stop_position, 0.0};  // unload the stop: the command returns to where the axis stands
  const int back = -hard_->direction;
  if (rules_.vendor_methods == profile::HomingVendorMethods::TorqueLimit) {
    if (!hard_->index_after) {
      found(s, stop_position);
      return;
    }
    edge_position_ = stop_position;
    leg_ = {Phase::IndexSearch, back, v_zero_};
    phase_ = Phase::IndexSearch;
    return;
  }
  // DS5C1 L3553-L3565: P7-20 index pulses back at 6099h-02h, then the P9-19 + 10000 * P9-20 pulse
  // distance at 6099h-01h (taken in user units, the command pulses of the bus), then zero.
  const double distance = static_cast<double>(fixed_low_.get()) + 10000.0 * static_cast<double>(fixed_high_.get());
  index_left_ = std::max(0, z_count_.get());
  fixed_target_ = stop_position + back * distance;
  if (index_left_ > 0) {
    leg_ = {Phase::PushIndex, back, v_zero_};
    phase_ = Phase::PushIndex;
  } else if (distance != 0.0) {
    leg_ = {Phase::FixedMove, back, v_switch_};
    phase_ = Phase::FixedMove;
  } else {
    found(s, stop_position);
  }
}

Setpoint HomingMode::step_push_index(const AxisSample& s) {
  // Every index pulse met on the way back from the stop counts (L3556).
  if (s.index_passed && --index_left_ <= 0) {
    const double z = s.index_position;
    cmd_.position = s.position_demand;
    cmd_.velocity = 0.0;
    const double distance = static_cast<double>(fixed_low_.get()) + 10000.0 * static_cast<double>(fixed_high_.get());
    if (distance == 0.0) {
      found(s, z);
      return hold();
    }
    // Stop on the index, then the fixed distance from where the command stood (L3565).
    fixed_target_ = cmd_.position + leg_.direction * distance;
    leg_ = {Phase::FixedMove, leg_.direction, v_switch_};
    phase_ = Phase::FixedMove;
    return hold();
  }
  return run(s, leg_.direction * leg_.speed);
}

Setpoint HomingMode::step_fixed_move(const AxisSample& s) {
  cmd_ = move_to(cmd_, fixed_target_, leg_.speed, acc_, acc_, s.dt_s);
  const Setpoint sp{Setpoint::Kind::Position, cmd_.position, cmd_.velocity};
  if (cmd_.position == fixed_target_ && cmd_.velocity == 0.0) found(s, fixed_target_);
  return sp;
}

void HomingMode::finish_pulse(const AxisSample& s) {
  if (s.time < pulse_end_) return;
  attained_ = true;
  phase_ = Phase::Idle;
  outcome_ = Outcome::Completed;
}

}  // namespace vdrive::drive
