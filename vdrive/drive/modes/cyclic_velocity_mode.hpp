#pragma once
// Cyclic synchronous velocity (csv, 6060h = 9): the master sends 60FFh every bus cycle (+ 60B1h
// where profile.drive.offsets_honoured: DS1000A-EC L3230-L3234; the DS5C1 ignores it), limited by
// 6080h (A6B L21741-L22455, DS1000A-EC L3236-L3246, DS5C1 L2905-L3001). Between set-points the
// demand moves linearly to the new one over one bus cycle, so the velocity loop sees no steps.
// 60B2h is the torque feed-forward where offsets are honoured. Halt ramps to standstill per 605Dh.
// Statusword bit 12: drive follows the command value (not while halted).
#include <cstdint>

#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/modes/cyclic_bus_cycle.hpp"
#include "vdrive/drive/modes/cyclic_halt.hpp"
#include "vdrive/drive/modes/cyclic_segment.hpp"

namespace vdrive::drive {

class CyclicVelocityMode final : public ModeHandler {
public:
  explicit CyclicVelocityMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::csv; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  std::uint16_t status_bits() const override { return status_; }
  void on_cycle(Nanos now) override { cycle_.on_cycle(now); }

  bool limited() const { return limited_; }   // the last target was cut to 6080h

private:
  std::int64_t bus_target() const;
  double max_speed() const;                   // user units/s; < 0 = none
  void restart_from(double velocity);

  const DriveContext& ctx_;
  ObjectRef<std::int32_t> target_, velocity_offset_;
  ObjectRef<std::int16_t> torque_offset_;
  ObjectRef<std::uint32_t> max_motor_speed_;
  CyclicBusCycle cycle_;
  CyclicHalt halt_;
  CyclicSegment segment_;
  std::int64_t last_target_ = 0;
  double output_ = 0.0;
  bool halted_ = false;
  bool limited_ = false;
  std::uint16_t status_ = 0;
};

}  // namespace vdrive::drive
