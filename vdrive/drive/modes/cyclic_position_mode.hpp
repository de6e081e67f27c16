#pragma once
// Cyclic synchronous position (csp, 6060h = 8). The master sends an absolute target every bus
// cycle: 607Ah + 60B0h (the offset only where profile.drive.offsets_honoured; the DS5C1 accepts
// and ignores 60B0h-60B2h, L10025-L10039), with 60B1h/60B2h as velocity/torque feed-forward. The
// demand moves linearly to each set-point over one bus cycle (CyclicSegment) and never faster
// than 6080h allows:
//  * A6B: a per-cycle step beyond the 6080h-derived limit is Err27.4 (pending_alarm() returns
//    profile.drive.alarms.position_command_jump), unless 3722h bit 5 saturates the step instead
//    (L16918-L17124). The first set-point is measured from the demand at enable, so a master that
//    does not keep 607Ah on 6064h while disabled gets the alarm (L16793-L16871).
//  * DS1000A-EC (profile.drive.csp_clamps_to_max_speed): the followed position is limited to what
//    6080h allows and catches up at that speed (L2283-L2292, L2319-L2331).
// Statusword: bit 12 drive follows the command value (not while halted), bit 13 following error.
#include <cstdint>
#include <string_view>

#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/modes/cyclic_bus_cycle.hpp"
#include "vdrive/drive/modes/cyclic_following_error.hpp"
#include "vdrive/drive/modes/cyclic_halt.hpp"
#include "vdrive/drive/modes/cyclic_segment.hpp"
#include "vdrive/drive/motion_ramp.hpp"

namespace vdrive::drive {

class CyclicPositionMode final : public ModeHandler {
public:
  explicit CyclicPositionMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::csp; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  std::uint16_t status_bits() const override { return status_; }
  void on_cycle(Nanos now) override { cycle_.on_cycle(now); }
  std::string_view pending_alarm() override { return pending_alarm_; }

  bool clamped() const { return clamped_; }   // the last set-point was limited by 6080h

private:
  std::int64_t bus_target() const;
  double step_limit(Nanos period) const;      // user units per bus cycle; < 0 = none
  void take_set_point(Nanos at, std::int64_t target);
  void restart_from(double position);

  const DriveContext& ctx_;
  ObjectRef<std::int32_t> target_, position_offset_, velocity_offset_;
  ObjectRef<std::int16_t> torque_offset_;
  ObjectRef<std::uint32_t> max_motor_speed_;
  ObjectRef<std::int16_t> saturation_setup_;  // A6B 3722h, bit 5 (absent elsewhere)
  CyclicBusCycle cycle_;
  CyclicHalt halt_;
  CyclicFollowingError following_error_;
  CyclicSegment segment_;
  MotionState halting_{};
  bool halted_ = false;
  std::int64_t last_target_ = 0;   // previous bus set-point (607Ah + 60B0h)
  double goal_ = 0.0;              // where the demand is heading (the set-point after limiting)
  double output_ = 0.0;
  bool clamped_ = false;
  std::string_view pending_alarm_;
  std::uint16_t status_ = 0;
};

}  // namespace vdrive::drive
