#pragma once
// The CiA 402 homing methods (6098h) as data: one row per standard method saying which switch's
// edge is the reference, from which side the final approach crosses it, whether the home is the
// first index pulse after that edge, and which way to start when the switch state does not say.
// Sources: A6B L17785-L17890 (table), L18740-L19346 (method texts); DS5C1 L3272-L3321,
// L3570-L3673; DS1000A-EC L2766-L2956. The vendor methods (< 0) differ per product and are
// listed in the product's homing section (homing_rules.hpp).
//
// Geometry words used below: a switch is "active below" its edge (negative limit, the negative home
// switch of 5/6), "active above" it (positive limit, positive home switch of 3/4) or a window with a
// lower and an upper edge (the home switch of 7-14 / 23-30, a limit switch further out).
#include <cstdint>

namespace vdrive::drive {

enum class HomingSwitch : std::uint8_t { None, NegativeLimit, PositiveLimit, Home };

enum class SwitchShape : std::uint8_t { ActiveBelow, ActiveAbove, Window };

enum class HomingKind : std::uint8_t {
  SwitchEdge,       // 1-14, 17-30: a switch edge, optionally followed by the index pulse
  IndexOnly,        // 33, 34: the next index pulse in one direction
  CurrentPosition,  // 35, 37: no motion; here is home
};

struct HomingMethodSpec {
  std::int8_t method = 0;
  HomingKind kind = HomingKind::SwitchEdge;
  HomingSwitch reference = HomingSwitch::None;  // the switch whose edge is the reference
  SwitchShape shape = SwitchShape::ActiveBelow;
  bool upper_edge = false;       // the window's upper edge (else the lower one); fixed by shape otherwise
  int final_direction = +1;      // direction of the final approach across the edge (and the index search)
  bool index = false;            // home = first index pulse beyond the edge in final_direction
  int initial_direction = +1;    // Window only: first move when the home switch is inactive at start
  HomingSwitch reversal_limit = HomingSwitch::None;  // Window only: limit that turns the search round
};

// The standard method `method` (1-14, 17-30, 33, 34, 35, 37), or nullptr (vendor or undefined).
const HomingMethodSpec* find_standard_homing_method(std::int8_t method);

}  // namespace vdrive::drive
