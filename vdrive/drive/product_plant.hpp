#pragma once
// The plant a product's data gives: motor parameters from its motor catalogue
// (profiles/<id>/motors.yaml, family from drive.stepper), and the default plant a drive gets when no
// plant file is given. The plant itself takes these as plain values. The manuals leave most
// electrical and mechanical data out (see the catalogue's comments), so every field the catalogue
// leaves at 0 is filled by a documented rule of thumb (docs/plant.md, "Defaults") rather than
// invented per model.
#include "plant/motor_catalogue.hpp"
#include "plant/plant_description.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

// `drive.stepper` says which family the motor belongs to (stepper or servo).
plant::MotorParams motor_params_from(const profile::MotorSpec& spec, const profile::DriveSpec& drive);

// The product's default motor: its first catalogue entry (or the family's fallback if empty).
plant::MotorParams default_motor(const profile::ProductProfile& product);

// One rotary axis named after the product: default motor, direct drive, a load inertia equal to
// the rotor's, light friction, the catalogue's encoder. What `vdrive run --drive <id>` gets.
plant::PlantDescription default_plant(const profile::ProductProfile& product);

// Every catalogue motor as plant values, for plant files naming the product.
plant::MotorCatalogue motor_catalogue(const profile::ProductProfile& product);

}  // namespace vdrive::drive
