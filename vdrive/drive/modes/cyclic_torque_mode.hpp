#pragma once
// Cyclic synchronous torque (cst, 6060h = 10): the master sends 6071h every bus cycle (+ 60B2h
// where profile.drive.offsets_honoured; the DS5C1 does not support 60B2h in cst, L3018-L3167).
// The torque limits (6072h, 60E0h/60E1h, the product clamp) are MotionLimits' business; the mode
// keeps the speed under the torque-mode cap: min(profile.drive.torque_mode_speed_cap_rpm, 6080h)
// (DS1000A-EC 500 r/min, L3377-L3381, L1283-L1289), 6080h alone elsewhere (A6B L24416-L24452,
// DS5C1 L3018-L3167). Above the cap the torque is tapered to zero over 5 % of the cap and turns
// into braking beyond, a proportional speed limiter. Halt: 605Dh 1/2 ramp the torque to 0 at
// 6087h, 3 drops it at once. Statusword bit 12: drive follows the command value, 0 while halted or
// speed-limited (A6B L24628-L24640).
#include <cstdint>

#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/modes/cyclic_halt.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class CyclicTorqueMode final : public ModeHandler {
public:
  explicit CyclicTorqueMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::cst; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  std::uint16_t status_bits() const override { return status_; }

  bool speed_limited() const { return speed_limited_; }
  double speed_cap() const;                   // user units/s; < 0 = none

private:
  const DriveContext& ctx_;
  ObjectRef<std::int16_t> target_, torque_offset_;
  ObjectRef<std::uint32_t> max_motor_speed_;
  CyclicHalt halt_;
  double output_ = 0.0;
  bool halted_ = false;
  bool speed_limited_ = false;
  std::uint16_t status_ = 0;
};

}  // namespace vdrive::drive
