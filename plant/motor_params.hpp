#pragma once
// Motor data for the physics from a product's motor catalogue (profiles/<id>/motors.yaml), and the
// default plant a drive gets when no plant file is given. The manuals leave most electrical and
// mechanical data out (see the catalogue's comments), so every field the catalogue leaves at 0 is
// filled by a documented rule of thumb (docs/plant.md, "Defaults") rather than invented per model.
#include <string_view>

#include "plant/plant_description.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::plant {

// `product_id` says which family the motor belongs to ("ds1000a" = stepper, others servo).
MotorParams motor_params_from(std::string_view product_id, const profile::MotorSpec& spec);

// The product's default motor: its first catalogue entry (or the family's fallback if empty).
MotorParams default_motor(const profile::ProductProfile& product);

// One rotary axis named after the product: default motor, direct drive, a load inertia equal to
// the rotor's, light friction, the catalogue's encoder. What `vdrive run --drive <id>` gets.
PlantDescription default_plant(const profile::ProductProfile& product);

}  // namespace vdrive::plant
