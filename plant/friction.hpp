#pragma once
// Load-side friction, Stribeck form. The static/Coulomb part is applied as an ODE joint motor with
// target velocity 0 and this force limit (so a joint truly sticks below breakaway instead of
// chattering), the viscous part as an explicit force.
#include <cmath>

#include "plant/plant_description.hpp"

namespace vdrive::plant {

// Magnitude of the dry (Coulomb + Stribeck) friction at speed |v|.
inline double dry_friction(const FrictionSpec& f, double v) {
  const double fs = f.breakaway > 0 ? f.breakaway : f.coulomb;
  if (f.stribeck_velocity <= 0) return f.coulomb;
  const double r = v / f.stribeck_velocity;
  return f.coulomb + (fs - f.coulomb) * std::exp(-r * r);
}

}  // namespace vdrive::plant
