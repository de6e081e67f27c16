#include "vdrive/drive/modes/profile_position.hpp"

#include <algorithm>
#include <cmath>

namespace vdrive::drive {

namespace {
constexpr Nanos ms(std::uint32_t v) { return static_cast<Nanos>(v) * 1'000'000; }

// 60F2h fields (A6B L15044-L15053, DS1000A-EC L1848-L1850).
constexpr unsigned relative_option(std::uint16_t code) { return code & 0x3u; }
constexpr unsigned request_response_option(std::uint16_t code) { return (code >> 4) & 0x3u; }
}  // namespace

ProfilePositionMode::ProfilePositionMode(const DriveContext& ctx)
    : ctx_(ctx), profile_(ctx), target_position_(ctx.objects, 0x607A), profile_velocity_(ctx.objects, 0x6081),
      option_code_(ctx.objects, 0x60F2), motion_profile_type_(ctx.objects, 0x6086),
      position_window_(ctx.objects, 0x6067), following_error_window_(ctx.objects, 0x6065),
      position_window_time_(ctx.objects, 0x6068), following_error_time_(ctx.objects, 0x6066) {}

void ProfilePositionMode::activate(const AxisSample& s) {
  // Transition 4 clears all earlier set-points (A6B L9618ff); after another mode the previous
  // target is gone, so relative option 0 counts from 0 (A6B L15077-L15081).
  demand_ = {s.position_demand, s.velocity_demand};
  has_exec_ = has_buffer_ = false;
  last_target_ = 0.0;
  bit4_seen_ = true;  // a set-point needs a 0->1 seen in this mode
  bit4_released_ = false;
  acknowledged_ = false;
  replan_ = true;
  in_window_.reset();
  following_error_.reset();
  status_ = 0;
}

ProfilePositionMode::Task ProfilePositionMode::latch_task(const AxisSample& s, std::uint16_t controlword) const {
  Task t;
  t.target = static_cast<double>(target_position_.get());
  if (controlword & cw::relative) {
    switch (relative_option(option_code_.get())) {
      case 1: t.target += demand_.position; break;  // 6062h
      case 2: t.target += s.position; break;        // 6064h
      default: t.target += last_target_; break;     // 0 previous target (3 reserved: as 0)
    }
  }
  t.velocity = std::min(static_cast<double>(profile_velocity_.get()), profile_.velocity_limit());
  t.acc = profile_.acceleration();
  t.dec = profile_.deceleration();
  t.continuous = ctx_.profile.drive.pp.change_on_set_point && (controlword & cw::change_on_set_point);
  return t;
}

void ProfilePositionMode::accept_set_point(const AxisSample& s, std::uint16_t controlword, bool halted) {
  const bool immediate = controlword & cw::change_set_immediately;
  acknowledged_ = true;
  if (halted && immediate && ctx_.profile.drive.pp.halt_discards_on_immediate) {
    // DS1000A-EC L2111-L2117: the target is dropped, the actual position becomes the target and
    // the drive stays there after the halt ends.
    has_exec_ = has_buffer_ = false;
    demand_ = {s.position, 0.0};
    last_target_ = s.position;
    return;
  }
  const Task t = latch_task(s, controlword);
  if (t.velocity <= 0.0) return;  // 6081h = 0 (or a 0 limit): dropped, no motion (A6B L15464, DS5C1 L3913)
  if (!has_exec_ || immediate) {   // bit 5: the running move and the buffer give way (A6B L15749-L15755)
    has_buffer_ = false;
    last_target_ = t.target;
    start(t);
    return;
  }
  if (ctx_.profile.drive.pp.buffered_set_point && !has_buffer_) {
    buffer_ = t;
    has_buffer_ = true;
    last_target_ = t.target;
  }
  // Otherwise not taken: the buffer is full (A6B L15745-L15747), or the product has none and needs
  // the set-point again after the move (DS5C1 L3764).
}

void ProfilePositionMode::start(const Task& t) {
  exec_ = t;
  has_exec_ = true;
  sin2_active_ = ctx_.profile.drive.pp.sin2_profile && motion_profile_type_.get() == 1;
  replan_ = true;
}

void ProfilePositionMode::advance(const AxisSample& s) {
  const double dt = s.dt_s;
  if (!has_exec_) {  // nothing to run: come to rest where we are
    demand_ = ramp_velocity(demand_, 0.0, profile_.acceleration(), profile_.deceleration(), dt);
    return;
  }
  // Bit 9 (DS1000A-EC L2081-L2086): run through the current target at its speed toward the
  // buffered one, unless the direction reverses.
  const bool run_on = has_buffer_ && buffer_.continuous &&
                      (exec_.target - demand_.position) * (buffer_.target - exec_.target) > 0.0;
  const double goal = run_on ? buffer_.target : exec_.target;
  MotionState next;
  if (sin2_active_) {
    if (replan_ || sin2_.target() != goal) sin2_.plan(demand_, goal, exec_.velocity, exec_.acc, exec_.dec);
    replan_ = false;
    next = sin2_.step(dt);
  } else {
    next = move_to(demand_, goal, exec_.velocity, exec_.acc, exec_.dec, dt);
  }
  const double direction = exec_.target - demand_.position;
  demand_ = next;
  if (run_on) {
    if ((demand_.position - exec_.target) * direction >= 0.0) {  // passed: the next task's speed applies
      has_buffer_ = false;
      start(buffer_);
    }
    return;
  }
  if (demand_.position == exec_.target && demand_.velocity == 0.0) {
    if (has_buffer_) {
      has_buffer_ = false;
      start(buffer_);
    } else {
      has_exec_ = false;
    }
  }
}

Setpoint ProfilePositionMode::step(const AxisSample& s, std::uint16_t controlword) {
  const bool halted = controlword & cw::halt;
  const bool bit4 = controlword & cw::new_set_point;
  if (!bit4) bit4_released_ = false;
  if (bit4 && !bit4_seen_) accept_set_point(s, controlword, halted);
  bit4_seen_ = bit4;

  if (halted) {  // pause: the task stays and resumes on release (A6B L15834-L15857)
    demand_ = ramp_velocity(demand_, 0.0, profile_.acceleration(), profile_.halt_deceleration(), s.dt_s);
    replan_ = true;
  } else {
    advance(s);
  }

  // 60F2h rro: 01 releases bit 4 when the move completes, 10 as soon as a new set-point can be
  // taken (A6B L15249-L15267, DS1000A-EC L1899-L1910).
  const unsigned rro = request_response_option(option_code_.get());
  if (bit4 && acknowledged_ && ((rro == 2 && !has_buffer_) || (rro == 1 && !has_exec_ && !has_buffer_)))
    bit4_released_ = true;
  // Bit 12 stays 1 while bit 4 is held or a set-point waits in the buffer (A6B L15439-L15449).
  if ((!bit4 || bit4_released_) && !has_buffer_) acknowledged_ = false;

  update_status(s, halted);
  Setpoint sp;
  sp.kind = Setpoint::Kind::Position;
  sp.position = demand_.position;
  sp.velocity = demand_.velocity;
  return sp;
}

void ProfilePositionMode::update_status(const AxisSample& s, bool halted) {
  std::uint16_t bits = acknowledged_ ? sw::oms12 : 0;
  bool reached = false;
  if (halted) {  // halt: 1 once the axis stands (A6B L14186-L14193)
    in_window_.reset();
    reached = demand_.velocity == 0.0 && s.stopped;
  } else {
    const bool done = !has_exec_ && !has_buffer_;
    const bool inside = std::abs(demand_.position - s.position) <= static_cast<double>(position_window_.get());
    reached = in_window_.update(done && inside, s.time, ms(position_window_time_.get()));
  }
  if (reached) bits |= sw::target_reached;
  const bool lagging = std::abs(s.position_demand - s.position) > static_cast<double>(following_error_window_.get());
  if (following_error_.update(lagging, s.time, ms(following_error_time_.get()))) bits |= sw::oms13;
  status_ = bits;
}

void ProfilePositionMode::stopped_by_limit(const Setpoint& applied) {
  // Without this the trajectory ran on to the target beyond the limit while the axis stood at it:
  // a later move back waited until that demand had travelled back to the limit.
  demand_ = {applied.position, applied.velocity};
  has_exec_ = has_buffer_ = false;
  replan_ = true;
}

void ProfilePositionMode::idle(const AxisSample& s, std::uint16_t controlword) {
  demand_ = {s.position, s.velocity};
  has_exec_ = has_buffer_ = false;
  const bool bit4 = controlword & cw::new_set_point;
  bit4_seen_ = bit4;
  if (!bit4) acknowledged_ = false;
  in_window_.reset();
  following_error_.reset();
  status_ = acknowledged_ ? sw::oms12 : 0;
}

}  // namespace vdrive::drive
