#pragma once
// Profile velocity mode (pv, 6060h = 3): ramps the velocity demand to 60FFh (+ 60B1h where the
// product honours offsets, profile.drive.offsets_honoured; DS5C1 L4002-L4158 does not) with
// 6083h/6084h, limited by min(607Fh, 6080h) as they were when the axis last stood still (A6B
// L21708-L21714: changes during motion are not applied).
//   - bit 10 target reached: |60FFh + 60B1h - 606Ch| <= 606Dh for 606Eh ms; with halt, the axis
//     stopped (A6B L21485-L21507, DS1000A-EC L3102-L3115);
//   - bit 12 speed: 1 while |606Ch| <= 606Fh, 0 once above it for 6070h ms (A6B L21585-L21591; the
//     DS1000A-EC text L3119-L3125 says the opposite, its table the standard: standard kept);
//   - halt decelerates by 605Dh and the target is taken up again on release (DS1000A-EC L886-L888).
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/hold_timer.hpp"
#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/modes/profile_objects.hpp"
#include "vdrive/drive/motion_ramp.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class ProfileVelocityMode final : public ModeHandler {
public:
  explicit ProfileVelocityMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::pv; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  std::uint16_t status_bits() const override { return status_; }

  // The speed limit in force (user units/s), for tests and the engine's bit 11.
  double velocity_limit() const { return limit_; }

private:
  double commanded() const;  // 60FFh (+ 60B1h)
  void update_speed_bit(const AxisSample& s);

  const DriveContext& ctx_;
  ProfileObjects profile_;
  ObjectRef<std::int32_t> target_velocity_, velocity_offset_;
  ObjectRef<std::uint32_t> velocity_window_, velocity_threshold_;
  ObjectRef<std::uint16_t> velocity_window_time_, velocity_threshold_time_;

  MotionState demand_{};
  double limit_ = 0.0;
  HoldTimer in_window_, above_threshold_;
  bool speed_bit_ = true;
  std::uint16_t status_ = 0;
};

}  // namespace vdrive::drive
