#pragma once
// One mode of operation (6060h value) of the drive: turns the mode's objects (targets, profile
// parameters) and controlword bits into a set-point per control step, and reports the mode's
// statusword bits (10 target reached, 12, 13). The engine owns the power state: it calls step()
// only in Operation enabled while no stop sequence runs, and idle() otherwise. Halt (6040h bit 8)
// is the mode's business, because each mode halts differently (605Dh, homing aborts).
// Implementations allocate nothing after construction.
#include <cstdint>
#include <string_view>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/drive_types.hpp"
#include "vdrive/drive/mapped_outputs.hpp"

namespace vdrive::drive {

class ModeHandler {
public:
  virtual ~ModeHandler() = default;

  virtual std::int8_t mode() const = 0;

  // The mode takes over (mode switch, or Operation enabled begins: transition 4/16 clears earlier
  // set-points). `s` says where the axis is; the first set-point must continue from
  // s.position_demand / s.velocity_demand without a jump.
  virtual void activate(const AxisSample& s) = 0;

  // One control step in Operation enabled. `controlword` is 6040h as the master last wrote it.
  virtual Setpoint step(const AxisSample& s, std::uint16_t controlword) = 0;

  // The power stage is off or a stop sequence runs: follow the axis (s.position) so that a later
  // activate() starts from where it is, and keep the mode's status bits true.
  virtual void idle(const AxisSample& /*s*/, std::uint16_t /*controlword*/) {}

  // Bits 10, 12, 13 of 6041h (sw::mode_bits) after the last step()/idle().
  virtual std::uint16_t status_bits() const = 0;

  // A software position limit changed this step's set-point (MotionLimits): `applied` is what the
  // axis was commanded. A mode that plans its own trajectory continues from there instead of from
  // the demand it asked for, which the axis never took.
  virtual void stopped_by_limit(const Setpoint& /*applied*/) {}

  // Homing: true once when home was found in this step; `position` (current user frame) is where
  // the reference point is, the engine re-references so that it reads 607Ch.
  virtual bool take_home_found(double& /*position*/) { return false; }

  // Cyclic modes: new set-points arrived from the bus (outputs taken over at SYNC0 / SM2 event).
  virtual void on_cycle(Nanos /*now*/) {}
  // A PDO mapping became effective: `outputs` are the objects the RxPDO now carries.
  virtual void outputs_mapped(const MappedOutputs& /*outputs*/) {}

  // A vendor alarm code (profile alarms.yaml) the mode detected, e.g. A6B Err27.4 for a csp
  // set-point jump; empty when none. The engine raises it (raising an active alarm is a no-op).
  virtual std::string_view pending_alarm() { return {}; }
};

}  // namespace vdrive::drive
