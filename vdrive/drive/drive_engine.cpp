#include "vdrive/drive/drive_engine.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/round.hpp"
#include "ethercat/little_endian.hpp"

#include "vdrive/drive/control/motor_setpoint.hpp"
#include "vdrive/drive/modes/cyclic_position_mode.hpp"
#include "vdrive/drive/modes/cyclic_torque_mode.hpp"
#include "vdrive/drive/modes/cyclic_velocity_mode.hpp"
#include "vdrive/drive/modes/homing_mode.hpp"
#include "vdrive/drive/modes/interpolated_position.hpp"
#include "vdrive/drive/modes/profile_position.hpp"
#include "vdrive/drive/modes/profile_torque.hpp"
#include "vdrive/drive/modes/profile_velocity.hpp"

namespace vdrive::drive {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// A loop that fell this far behind (a debugger, a stopped process) resumes from now instead of
// replaying every missed step.
constexpr Nanos kMaxCatchUp = 100'000'000;

std::unique_ptr<ModeHandler> make_handler(std::int8_t m, const DriveContext& ctx) {
  switch (m) {
    case mode::pp: return std::make_unique<ProfilePositionMode>(ctx);
    case mode::pv: return std::make_unique<ProfileVelocityMode>(ctx);
    case mode::tq: return std::make_unique<ProfileTorqueMode>(ctx);
    case mode::hm: return std::make_unique<HomingMode>(ctx);
    case mode::ip: return std::make_unique<InterpolatedPositionMode>(ctx);
    case mode::csp: return std::make_unique<CyclicPositionMode>(ctx);
    case mode::csv: return std::make_unique<CyclicVelocityMode>(ctx);
    case mode::cst: return std::make_unique<CyclicTorqueMode>(ctx);
    default: return nullptr;  // vl and vendor modes: not run
  }
}

std::int32_t saturate_i32(double v) {
  if (!(v == v)) return 0;
  return static_cast<std::int32_t>(std::clamp<std::int64_t>(round_to_int64(std::clamp(v, -2.2e9, 2.2e9)), INT32_MIN, INT32_MAX));
}

std::int16_t saturate_i16(double v) {
  if (!(v == v)) return 0;
  return static_cast<std::int16_t>(std::clamp<std::int64_t>(round_to_int64(std::clamp(v, -40000.0, 40000.0)), -32768, 32767));
}

}  // namespace

DriveEngine::DriveEngine(const profile::ProductProfile& profile, od::ObjectStore& objects, plant::Plant& plant,
                         std::size_t axis, const plant::AxisSpec& axis_spec,
                         AlarmManager::EmergencySink emergencies)
    : profile_(profile),
      objects_(objects),
      plant_(plant),
      axis_(axis),
      ctx_{profile, objects, units_},
      obj_(objects),
      vendor_monitors_(objects, profile.drive.monitors),
      pds_(ctx_),
      stop_(ctx_),
      selector_(ctx_),
      limits_(ctx_),
      alarms_(ctx_, std::move(emergencies)),
      monitors_(ctx_, alarms_),
      io_(ctx_),
      probe_(ctx_),
      axis_spec_(axis_spec) {
  loop_ = make_control_loop(ctx_, axis_spec_.motor);
  for (std::int8_t m : profile.modes.modes) {
    if (m <= 0 || m >= static_cast<std::int8_t>(handlers_.size())) continue;
    handlers_[static_cast<std::size_t>(m)] = make_handler(m, ctx_);
  }
  homing_ = static_cast<HomingMode*>(handlers_[mode::hm].get());
  for (std::size_t i = 0; i < kInjectedFaultCount; ++i) {
    const std::string& code = alarm_code_for(profile.drive.alarms, static_cast<InjectedFault>(i));
    injected_alarms_[i] = code.empty() ? nullptr : alarms_.find(code);
  }
  period_ = std::max<Nanos>(static_cast<Nanos>(profile.drive.control_period_ns), 1000);
  // The panel's alarm clear as an object (DS5C1 F0-00 = 4000h, write 1, L7408-L7412): the write is
  // taken (any value is stored, the manual gives no range) and the next control step clears the
  // alarms through the alarm manager's drive-side clear, as the panel does.
  const profile::AlarmRulesSpec& rules = profile.drive.alarm_rules;
  if (rules.drive_clear_index != 0 && objects.dictionary().find(rules.drive_clear_index, rules.drive_clear_subindex)) {
    objects.on_write(rules.drive_clear_index,
                     [request = drive_clear_request_, sub = rules.drive_clear_subindex,
                      value = rules.drive_clear_value](const od::EntryDesc& e, std::span<const std::uint8_t> data) {
                       if (e.subindex == sub && ecat::get_le(data) == value) *request = true;
                       return od::SdoAbort::Ok;
                     });
  }
}

DriveEngine::~DriveEngine() = default;

ModeHandler* DriveEngine::handler_for(std::int8_t m) const {
  if (m <= 0 || m >= static_cast<std::int8_t>(handlers_.size())) return nullptr;
  return handlers_[static_cast<std::size_t>(m)].get();
}

void DriveEngine::latch_units() {
  const FactorGroup f = factor_group({obj_.encoder_increments.get(), obj_.encoder_revolutions.get(), obj_.gear_motor.get(),
                                      obj_.gear_shaft.get(), obj_.feed.present(), obj_.feed.get(), obj_.feed_shaft.get(),
                                      obj_.polarity.get()},
                                     axis_spec_.encoder.counts_per_rev);
  // Keep the user position where it is across the change (the axis did not move).
  const double angle = plant_.feedback(axis_).motor_angle_rad;
  const double before = units_.position_to_user(angle - zero_rad_) + offset_user_;
  units_.apply(f);
  offset_user_ = before - units_.position_to_user(angle - zero_rad_);
}

void DriveEngine::power_on(Nanos now) {
  const plant::AxisFeedback& fb = plant_.feedback(axis_);
  // Absolute encoders report the position they hold; incremental ones start counting at 0.
  zero_rad_ = axis_spec_.encoder.absolute ? 0.0 : fb.motor_angle_rad;
  offset_user_ = 0.0;
  units_ = UnitScaling{};
  latch_units();
  offset_user_ = 0.0;
  pds_.power_on();
  selector_.power_on();
  *drive_clear_request_ = false;
  alarms_.power_on();
  monitors_.power_on();
  io_.power_on();
  probe_.power_on();
  if (homing_) {
    homing_->clear_attained();
    if (axis_spec_.encoder.absolute && profile_.drive.soft_limits == profile::SoftLimitRule::Always)
      homing_->set_attained();  // absolute encoder: the position is established (A6B L18222)
  }
  active_ = handler_for(selector_.active());
  loop_->reset(fb);
  last_ = Setpoint{};
  sample_ = measure(now, fb);
  demand_position_ = sample_.position;
  demand_velocity_ = 0.0;
  last_.position = demand_position_;
  previous_inputs_ = fb.inputs;
  powered_ = was_enabled_ = homed_ = false;
  cycle_pending_ = false;
  next_step_ = now;
  epoch_ = now - plant_.time();
  obj_.statusword.set(pds_.statusword());
  publish(sample_, fb);
}

void DriveEngine::esm_changed(ecat::AlState from, ecat::AlState to, Nanos now, bool by_error) {
  using ecat::AlState;
  if (to == AlState::Init) probe_.cancel();
  if (from == AlState::Init && to == AlState::PreOp) {
    if (homing_) homing_->clear_attained();
    // The reference is gone with homing attained: 607Dh after-homing limits wait for the next
    // homing run (A6B incremental, L13156).
    homed_ = false;
    latch_units();
  }
  if (from == AlState::PreOp && to == AlState::SafeOp) latch_units();  // startup SDOs are written by now
  if (!by_error && from == AlState::Op && ecat::rank(to) < ecat::rank(from) && pds_.power_stage_on())
    raise_cause(profile_.drive.alarms.esm_change_while_enabled, now);
}

void DriveEngine::outputs_taken(Nanos now) {
  for (auto& h : handlers_)
    if (h) h->on_cycle(now);
}

void DriveEngine::outputs_mapped(const MappedOutputs& outputs) {
  for (auto& h : handlers_)
    if (h) h->outputs_mapped(outputs);
}

bool DriveEngine::raise_alarm(std::string_view code, Nanos now) {
  const profile::AlarmSpec* a = alarms_.find(code);
  if (!a) return false;
  alarms_.raise(*a, now);
  return true;
}

bool DriveEngine::raise_al_error(std::uint16_t al_status_code, Nanos now) {
  for (const profile::AlarmSpec& a : profile_.alarms) {
    if (a.al_status_code != al_status_code) continue;
    alarms_.raise(a, now);
    return true;
  }
  return false;
}

void DriveEngine::raise_cause(std::string_view code, Nanos t) {
  if (code.empty()) return;
  if (const profile::AlarmSpec* a = alarms_.find(code)) alarms_.raise(*a, t);
}

void DriveEngine::set_injected_fault(InjectedFault fault, bool active, Nanos now) {
  injected_[fault_index(fault)] = active;
  if (active) {
    raise_injected(fault, now);
  } else if (const profile::AlarmSpec* a = injected_alarms_[fault_index(fault)]) {
    // The cause is gone; the monitors re-assert their own causes of the same alarm each step, and
    // another active fault with this alarm re-asserts it in the next step before any reset.
    alarms_.set_cause(*a, false);
  }
}

void DriveEngine::raise_injected(InjectedFault fault, Nanos t) {
  const profile::AlarmSpec* a = injected_alarms_[fault_index(fault)];
  if (!a) return;
  // A6B: main power loss with the servo off is no alarm (profiles/a6b/profile.yaml, L26690-L26840).
  if (removes_main_power(fault) && profile_.drive.alarms.supply_alarms_only_when_enabled &&
      !pds_.power_stage_on() && !alarms_.is_active(*a))
    return;
  alarms_.set_cause(*a, true);
  alarms_.raise(*a, t);   // no-op while active
}

bool DriveEngine::main_power_present() const {
  return main_power_ && !injected_[fault_index(InjectedFault::main_power_off)] &&
         !injected_[fault_index(InjectedFault::under_voltage)];
}

void DriveEngine::advance_to(Nanos now, const BusState& bus) {
  while (advance_one(now, bus)) {
  }
}

bool DriveEngine::advance_one(Nanos now, const BusState& bus) {
  if (next_step_ > now) return false;
  if (now - next_step_ > kMaxCatchUp) next_step_ = now - kMaxCatchUp;
  // `bus` was read at `now`; a step caught up late (a batch, a late wake) has the DC time of its
  // own instant, so a touch probe latches when the edge happened, not when the step ran.
  BusState at = bus;
  at.system_time_ns = bus.system_time_ns - static_cast<std::uint64_t>(now - next_step_);
  step(next_step_, at);
  next_step_ += period_;
  return true;
}

AxisSample DriveEngine::measure(Nanos t, const plant::AxisFeedback& fb) const {
  AxisSample s;
  s.time = t;
  s.dt_s = static_cast<double>(period_) * 1e-9;
  s.position = units_.position_to_user(fb.motor_angle_rad - zero_rad_) + offset_user_;
  s.velocity = units_.velocity_to_user(fb.motor_velocity_rad_s);
  const double rated = axis_spec_.motor.rated_torque_nm > 0 ? axis_spec_.motor.rated_torque_nm : 1.0;
  s.torque = units_.torque_sign() * fb.torque_nm / rated * 1000.0;
  s.position_demand = demand_position_;
  s.velocity_demand = demand_velocity_;
  s.torque_demand = last_.torque;
  s.inputs = 0;
  s.index_passed = fb.encoder.index_passed;
  if (s.index_passed) {
    const double cpr = axis_spec_.encoder.counts_per_rev > 0 ? axis_spec_.encoder.counts_per_rev : 1.0;
    const double back_rad = static_cast<double>(fb.encoder.counts - fb.encoder.index_counts) * kTwoPi / cpr;
    s.index_position = units_.position_to_user(fb.motor_angle_rad - back_rad - zero_rad_) + offset_user_;
  }
  s.stopped = stop_.stopped(s.velocity);
  s.referenced = homed_ || (homing_ && homing_->attained());
  return s;
}

void DriveEngine::rereference(double found_position) {
  // The point found reads 607Ch from now on (A6B L18429-L18433): new = old - found + 607Ch.
  const double shift = static_cast<double>(obj_.home_offset.get()) - found_position;
  offset_user_ += shift;
  demand_position_ += shift;
  last_.position += shift;
  sample_.position += shift;
  sample_.position_demand += shift;
  homed_ = true;
}

void DriveEngine::command(const Setpoint& sp, const plant::AxisFeedback& fb, double dt) {
  plant::AxisCommand cmd;
  const bool on = pds_.power_stage_on();
  if (on) {
    if (!powered_) loop_->reset(fb);
    const Setpoint limited = limits_.apply(sp, sample_, homing_ && homing_->running(), homed_);
    const double zero = zero_rad_ - units_.position_to_motor(offset_user_);
    const MotorSetpoint m = to_motor_setpoint(limited, units_, axis_spec_.motor.rated_torque_nm, zero,
                                              limits_.torque_limit_forward(), limits_.torque_limit_reverse());
    cmd = loop_->step(m, fb, dt);
    const double limit_nm = m.torque_limit_nm > 0 ? m.torque_limit_nm : axis_spec_.motor.peak_torque_nm;
    const double reverse_nm = m.torque_limit_reverse_nm > 0 ? m.torque_limit_reverse_nm : limit_nm;
    limits_.note_torque_saturated(!cmd.stepper_open_loop && limit_nm > 0 &&
                                  (cmd.torque_nm >= limit_nm * 0.999 || cmd.torque_nm <= -reverse_nm * 0.999));
    last_ = limited;
  } else {
    cmd.torque_nm = 0.0;
    last_ = Setpoint{Setpoint::Kind::Position, sample_.position, 0.0, 0.0, 0.0};
  }
  cmd.brake_released = !io_.brake_engaged(on);
  powered_ = on;
  plant_.command(axis_, cmd);

  // The demand as the next step sees it (6062h / 606Bh).
  switch (last_.kind) {
    case Setpoint::Kind::Position:
      demand_velocity_ = (last_.position - demand_position_) / dt;
      demand_position_ = last_.position;
      break;
    case Setpoint::Kind::Velocity:
      demand_velocity_ = last_.velocity;
      demand_position_ += last_.velocity * dt;
      break;
    case Setpoint::Kind::Torque:
      demand_velocity_ = sample_.velocity;
      demand_position_ = sample_.position;
      break;
  }
}

void DriveEngine::step(Nanos t, const BusState& bus) {
  const plant::AxisFeedback& fb = plant_.feedback(axis_);
  sample_ = measure(t, fb);
  const bool torque_off = profile_.drive.torque_off_input && torque_off_input_;
  sample_.inputs = io_.update(fb.inputs, torque_off, fb.encoder.index_passed);

  // Mode of operation: a change in Operation enabled hands over from where the demand is.
  const bool enabled_before = pds_.state() == PdsState::OperationEnabled;
  selector_.step(t, enabled_before);
  if (selector_.changed()) {
    active_ = handler_for(selector_.active());
    if (active_ && was_enabled_) active_->activate(sample_);
  }

  // Supervision: the vendor alarms whose causes the simulation can produce.
  const double rpm = sample_.velocity == 0.0 ? 0.0 : units_.user_to_rpm(sample_.velocity);
  MonitorInputs mi;
  mi.following_error_user = sample_.position_demand - sample_.position;
  mi.following_error_increments = mi.following_error_user * units_.increments_per_user();
  mi.following_error_revolutions = std::abs(units_.position_to_motor(mi.following_error_user)) / kTwoPi;
  mi.motor_speed_rpm = rpm;
  mi.max_motor_speed_rpm = static_cast<double>(obj_.max_motor_speed.get());
  mi.plant_faults = fb.faults;
  mi.torque_ratio = axis_spec_.motor.rated_torque_nm > 0 ? fb.torque_nm / axis_spec_.motor.rated_torque_nm : 0.0;
  mi.dt_s = sample_.dt_s;
  // Position deviation exists only while the position loop runs (pp, hm, ip, csp).
  mi.enabled = pds_.state() == PdsState::OperationEnabled && pds_.power_stage_on() &&
               last_.kind == Setpoint::Kind::Position && was_enabled_;
  mi.now = t;
  monitors_.step(mi);
  // Injected causes after the monitors, which reset the causes of the alarms they share.
  for (std::size_t i = 0; i < kInjectedFaultCount; ++i)
    if (injected_[i]) raise_injected(static_cast<InjectedFault>(i), t);
  if (active_) raise_cause(active_->pending_alarm(), t);
  raise_cause(probe_.pending_alarm(), t);
  if (profile_.drive.limit_switches == profile::LimitSwitchRule::Alarm && limits_.limit_switch_active())
    raise_cause(profile_.drive.alarms.limit_switch, t);

  // Cleared from the drive's side (DS5C1 4000h = 1): refused, as a fault reset, while a cause is
  // present or the fault reaction runs; no AL acknowledge needed (method 2, L7400-L7402).
  bool cleared_by_drive = false;
  if (*drive_clear_request_) {
    *drive_clear_request_ = false;
    cleared_by_drive = alarms_.clear_from_drive(pds_.state() == PdsState::FaultReactionActive, t);
  }

  // Power drive system.
  const std::uint16_t controlword = obj_.controlword.get();
  PdsConditions c;
  c.main_power = main_power_present();
  c.torque_off = torque_off;
  c.fault = alarms_.active();
  if (const profile::AlarmSpec* newest = alarms_.newest()) {
    c.fault_reaction = newest->reaction;
    c.fault_is_communication = alarms_.is_communication(*newest);
  }
  const bool reacting = pds_.state() == PdsState::FaultReactionActive;
  c.fault_reset_allowed = alarms_.reset_allowed(bus.al_error_pending, reacting, t);
  c.cleared_by_drive = cleared_by_drive;
  c.stopped = sample_.stopped;
  c.esm_init = bus.esm_init;
  c.mode = selector_.active();
  pds_.step(controlword, c);
  if (pds_.fault_reset_event()) alarms_.reset(bus.al_error_pending, t);
  // Main power lost in OE with 6007h = 1: A6B Err88.0 (L33767-L33774).
  if (pds_.abort_connection_fault()) raise_cause(profile_.drive.alarms.abort_connection, t);
  if (pds_.state() == PdsState::OperationEnabled && pds_.enabled_event()) {
    // Enabling without a mode that runs is the product's alarm (A6B Err88.1 L10625, DS5C1 E-881).
    if (!active_ || selector_.invalid_request()) raise_cause(profile_.drive.alarms.no_mode_at_enable, t);
  }
  if (pds_.stop_started()) stop_.start(pds_.stop(), selector_.active(), sample_, pds_.drive_side_action());

  // Set-point: the mode while motion is allowed, else the running stop, else hold.
  const bool motion = pds_.motion_allowed() && active_ != nullptr;
  Setpoint sp{Setpoint::Kind::Position, sample_.position_demand, 0.0, 0.0, 0.0};
  if (motion) {
    if (!was_enabled_) {
      // Transitions 4/16 clear earlier set-points: start from where the axis is (A6B L9715).
      demand_position_ = sample_.position_demand = sample_.position;
      demand_velocity_ = sample_.velocity_demand = 0.0;
      active_->activate(sample_);
    }
    sp = active_->step(sample_, controlword);
    double found = 0.0;
    if (active_->take_home_found(found)) {
      rereference(found);
      sp.position += static_cast<double>(obj_.home_offset.get()) - found;
    }
  } else {
    if (active_) active_->idle(sample_, controlword);
    if (pds_.stop() != StopKind::None) sp = stop_.step(sample_);
    else if (!pds_.power_stage_on()) sp.position = sample_.position;
  }
  was_enabled_ = motion;

  command(sp, fb, sample_.dt_s);
  if (motion && limits_.soft_limited()) active_->stopped_by_limit(last_);

  // Touch probe on the inputs of this step.
  probe_.step(previous_inputs_ | (torque_off ? din::torque_off : 0u),
              fb.inputs | (torque_off ? din::torque_off : 0u), sample_, bus.system_time_ns);
  previous_inputs_ = fb.inputs;

  std::uint16_t mode_bits = 0;
  if (active_ && (pds_.state() == PdsState::OperationEnabled || pds_.state() == PdsState::QuickStopActive))
    mode_bits = active_->status_bits() & sw::mode_bits;
  std::uint16_t status = pds_.statusword() | mode_bits;
  if (alarms_.warning()) status |= sw::warning;
  if (bus.remote) status |= sw::remote;
  if (limits_.internal_limit()) status |= sw::internal_limit;
  obj_.statusword.set(status);
  publish(sample_, fb);

  plant_.advance_to(t + period_ - epoch_);
}

void DriveEngine::publish(const AxisSample& s, const plant::AxisFeedback& fb) {
  obj_.position_actual.set(saturate_i32(s.position));
  obj_.position_internal.set(saturate_i32(s.position * units_.increments_per_user()));
  obj_.velocity_actual.set(saturate_i32(s.velocity));
  obj_.torque_actual.set(saturate_i16(s.torque));
  const double rated_a = axis_spec_.motor.rated_current_a > 0 ? axis_spec_.motor.rated_current_a : 1.0;
  obj_.current_actual.set(saturate_i16(std::abs(fb.current_a) / rated_a * 1000.0));
  obj_.position_demand.set(saturate_i32(demand_position_));
  obj_.position_demand_internal.set(saturate_i32(demand_position_));
  obj_.velocity_demand.set(saturate_i32(demand_velocity_));
  obj_.torque_demand.set(saturate_i16(last_.kind == Setpoint::Kind::Torque ? last_.torque : s.torque));
  obj_.following_error.set(saturate_i32(demand_position_ - s.position));
  if (vendor_monitors_.empty()) return;
  MonitorValues v;
  v.motor_speed_rpm = units_.user_to_rpm(s.velocity);
  v.speed_demand_rpm = units_.user_to_rpm(demand_velocity_);
  v.torque_demand_percent = static_cast<double>(obj_.torque_demand.get()) / 10.0;
  v.torque_actual_percent = s.torque / 10.0;
  v.motor_current_a = fb.current_a;   // signed with the torque (a servo's q-axis current)
  vendor_monitors_.publish(v);
}

}  // namespace vdrive::drive
