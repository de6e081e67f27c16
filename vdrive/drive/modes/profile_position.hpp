#pragma once
// Profile position mode (pp, 6060h = 1): the drive plans the move itself from 607Ah, 6081h and the
// accelerations, started by the set-point handshake (6040h bit 4 rising -> 6041h bit 12).
//   - one executing and one buffered set-point (profile.drive.pp.buffered_set_point; the DS5C1 drops
//     a set-point given mid-move without bit 5), bit 5 "change set immediately" replaces the running
//     move and empties the buffer (A6B L15724-L15757, DS1000A-EC L1993-L2080);
//   - bit 6 relative to the previous target / 6062h / 6064h by 60F2h bits 1-0 (A6B L15061-L15094,
//     DS1000A-EC L1954-L1966); 60F2h bits 5-4 release bit 4 by themselves (A6B L15241-L15267);
//   - bit 9 "change on set-point" only where the product has it (DS1000A-EC L1729-L1738);
//   - 6081h = 0: the set-point is acknowledged but dropped (A6B L14985, DS5C1 L3785);
//   - the speed is min(6081h, 607Fh, 6080h) taken when the set-point is accepted (A6B L15489-L15495);
//   - halt decelerates by 605Dh and resumes on release (A6B L15830-L15861); on the DS1000-EC a
//     set-point with bit 5 during halt drops the target and holds (L2111-L2117);
//   - 6086h = 1 gives a sin^2 ramp where the product has one (DS1000A-EC L1831-L1834);
//   - a software position limit that stops the move ends the executing and buffered set-points; the
//     demand continues from where the limit held it, so a move back starts at once (A6B
//     L13161-L13165, DS1000A-EC L1402);
//   - bit 10 target reached: all set-points done and |6062h - 6064h| <= 6067h for 6068h ms; with halt,
//     the axis stopped (A6B L14164-L14193); bit 13: |60F4h| > 6065h for 6066h ms (A6B L14279-L14314).
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/hold_timer.hpp"
#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/modes/profile_objects.hpp"
#include "vdrive/drive/modes/profile_sin2_move.hpp"
#include "vdrive/drive/motion_ramp.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class ProfilePositionMode final : public ModeHandler {
public:
  explicit ProfilePositionMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::pp; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  void stopped_by_limit(const Setpoint& applied) override;
  std::uint16_t status_bits() const override { return status_; }

  // For the engine and tests: a set-point is executing / waiting in the buffer.
  bool moving() const { return has_exec_; }
  bool buffered() const { return has_buffer_; }

private:
  // One positioning task as latched at acceptance (changes to 607Fh/6080h/6083h... act on the next).
  struct Task {
    double target = 0.0;
    double velocity = 0.0;
    double acc = 1.0, dec = 1.0;
    bool continuous = false;  // bit 9: run on into the next task without stopping
  };

  Task latch_task(const AxisSample& s, std::uint16_t controlword) const;
  void accept_set_point(const AxisSample& s, std::uint16_t controlword, bool halted);
  void start(const Task& t);
  void advance(const AxisSample& s);
  void update_status(const AxisSample& s, bool halted);

  const DriveContext& ctx_;
  ProfileObjects profile_;
  ObjectRef<std::int32_t> target_position_;
  ObjectRef<std::uint32_t> profile_velocity_;
  ObjectRef<std::uint16_t> option_code_;
  ObjectRef<std::int16_t> motion_profile_type_;
  ObjectRef<std::uint32_t> position_window_, following_error_window_;
  ObjectRef<std::uint16_t> position_window_time_, following_error_time_;

  MotionState demand_{};     // 6062h / 606Bh the mode commands
  Sin2Move sin2_;
  bool sin2_active_ = false;  // the executing task runs on the sin^2 planner
  Task exec_{}, buffer_{};
  bool has_exec_ = false, has_buffer_ = false;
  double last_target_ = 0.0;  // previous absolute target (60F2h relative option 0)
  bool bit4_seen_ = true;     // 6040h bit 4 as last seen (a set-point needs a fresh 0->1)
  bool bit4_released_ = false;  // 60F2h rro released bit 4 on the drive side
  bool acknowledged_ = false;
  bool replan_ = true;        // the sin^2 plan must be made again (new task, halt released)
  HoldTimer in_window_, following_error_;
  std::uint16_t status_ = 0;
};

}  // namespace vdrive::drive
