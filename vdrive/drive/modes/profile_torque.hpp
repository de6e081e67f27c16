#pragma once
// Profile torque mode (tq, 6060h = 4): ramps the torque demand to 6071h (+ 60B2h where the product
// honours offsets; DS5C1 L4330 does not) at the slope 6087h (0.1 %/s, 0 acts as 1), clamped by
// 6072h and the product's hard clamp (profile.drive.torque_clamp_permille: DS1000A-EC +-100.0 %,
// L3311). The further torque limits (60E0h/60E1h, vendor limits) are MotionLimits' business.
//   - speed limit: 6080h (A6B L24026, DS5C1 L4338), on the DS1000A-EC min(500 r/min, 6080h)
//     (profile.drive.torque_mode_speed_cap_rpm, L3315-L3318). When the axis runs at the cap with
//     the torque pushing it further, the step returns a Velocity set-point at the cap whose torque
//     limit is the torque demand, so the load still never sees more than the commanded torque;
//     speed_limited() reports it (the engine shows it in bit 11).
//   - halt by 605Dh: 1 and 2 ramp the torque to 0 at 6087h, 3 drops it to 0 at once (A6B
//     L27410-L27442, DS5C1 L4481); release ramps back to the target.
//   - bit 10 target reached: 6074h equals the target; with halt, the axis stopped (A6B
//     L23947-L23954, DS5C1 L4318-L4322). Bits 12 and 13 are unused.
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class ProfileTorqueMode final : public ModeHandler {
public:
  explicit ProfileTorqueMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::tq; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  std::uint16_t status_bits() const override { return status_; }

  // The last step ran at the speed limit (a Velocity set-point at the cap).
  bool speed_limited() const { return speed_limited_; }
  // The speed cap in force, user units/s.
  double speed_cap() const;
  // The torque demand (6074h), 0.1 % of rated.
  double torque_demand() const { return demand_; }

private:
  double commanded() const;  // 6071h (+ 60B2h), clamped

  const DriveContext& ctx_;
  ObjectRef<std::int16_t> target_torque_, torque_offset_, halt_option_;
  ObjectRef<std::uint32_t> torque_slope_, max_motor_speed_;
  ObjectRef<std::uint16_t> max_torque_;

  double demand_ = 0.0;
  bool speed_limited_ = false;
  std::uint16_t status_ = 0;
};

}  // namespace vdrive::drive
