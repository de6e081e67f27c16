#pragma once
// The ways the drive brings the motor to a standstill (CiA 402 option codes 605Ah-605Eh and the
// vendor's own "servo-side" stops), shared by PdsMachine (which one, and when it ends) and
// StopSequence (the set-points that carry it out).
#include <cstdint>

#include "vdrive/drive/drive_types.hpp"

namespace vdrive::drive {

enum class StopKind : std::uint8_t {
  None,
  Coast,          // power stage off at once, motor free (CiA 402 "disable drive function")
  SlowDown,       // 6084h profile deceleration; hm: 609Ah; tq/cst: 6087h torque slope to 0
  QuickStopRamp,  // 6085h quick stop deceleration; tq/cst: 6087h
  CurrentLimit,   // 60C6h max deceleration within the torque limit 6072h
  ZeroTorque,     // tq/cst: torque demand 0 at once, power stage stays on
  DriveSide,      // the vendor's own stop (A6B 3506h/3510h, DS5C1 P0-27/P0-29): see DriveSideAction
};

// What a DriveSide stop does physically, read from the vendor's sequence parameter when the stop
// starts. None = not resolved yet (StopSequence then reads the servo-off sequence itself).
enum class DriveSideAction : std::uint8_t {
  None,
  FreeRun,        // power stage off, motor coasts
  DynamicBrake,   // power stage off, windings shorted (the plant has no model of it yet: coasts)
  Decelerate,     // powered deceleration to standstill (DS5C1 P0-27/P0-29 = 2: within P0-31 ms)
  ImmediateStop,  // speed demand 0 at once within the emergency-stop torque (A6B 3511h)
};

// Torque modes ramp their torque (6087h) instead of their speed in every CiA 402 stop.
inline bool is_torque_mode(std::int8_t m) { return m == mode::tq || m == mode::cst; }

// The motor is left without power while this stop runs.
inline bool stop_frees_motor(StopKind kind, DriveSideAction action) {
  if (kind == StopKind::Coast) return true;
  if (kind != StopKind::DriveSide) return false;
  return action == DriveSideAction::FreeRun || action == DriveSideAction::DynamicBrake;
}

}  // namespace vdrive::drive
