#pragma once
// Faults of the machine an axis moves, switched on and off by a fault injector through
// Plant::set_axis_faults. Each lasts until the next call changes it; all default to "healthy".
// Jam and obstacle are joint stops (ODE limit rows), so they hold as hard as the machine's own end
// stops; load_scale scales the load body's own mass and inertia (not the reflected rotor);
// added_force adds to the load profile; friction_scale scales the load-side friction (Coulomb,
// breakaway and viscous alike: worn or dry guides, a failing bearing); brake_failure leaves an
// engaged brake without torque.
#include <optional>

namespace vdrive::plant {

struct AxisFaults {
  bool jam = false;                       // the load is seized: it cannot move (a stiff lock at its current position)
  std::optional<double> obstacle{};       // collision: a hard stop appears at this load position (load units), on the side the load approaches from
  double load_scale = 1.0;                // load change: the load's inertia/mass multiplied by this
  double added_force = 0.0;               // load change: extra external force/torque on the load
  double friction_scale = 1.0;            // load change: the load-side friction multiplied by this (>= 0)
  bool brake_failure = false;             // the holding brake does not hold when engaged
};

}  // namespace vdrive::plant
