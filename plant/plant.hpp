#pragma once
// A running plant: one ODE world holding the machine's bodies and joints, one axis per drive.
// The caller owns time (the scheduler's clock): advance_to(t) runs whole fixed steps of
// description.step_s, each made of `substeps` ODE steps, so results depend only on the
// description and the commands (deterministic). Stepping allocates nothing of its own.
//
// Per axis and step the drive gives an AxisCommand (torque, brake, or a stepper's open-loop
// angle) and reads an AxisFeedback (encoder, speeds, torque, temperatures, inputs, faults).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "common/clock.hpp"
#include "plant/axis_faults.hpp"
#include "plant/encoder.hpp"
#include "plant/plant_description.hpp"

namespace vdrive::plant {

// A description that cannot be built; what() names the axis/joint/body and field.
class PlantError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct AxisCommand {
  double torque_nm = 0.0;        // motor torque demand (servo, or stepper in closed loop)
  bool brake_released = true;    // false = holding brake engaged (if fitted)
  // Stepper open loop: when set, the drive imposes this motor angle (rad) with the given fraction
  // of rated current instead of a torque demand.
  bool stepper_open_loop = false;
  double stepper_angle_rad = 0.0;
  double stepper_current = 1.0;
};

namespace input {  // AxisFeedback::inputs bits
inline constexpr std::uint32_t negative_limit = 1u << 0;
inline constexpr std::uint32_t positive_limit = 1u << 1;
inline constexpr std::uint32_t home = 1u << 2;
inline constexpr std::uint32_t probe1 = 1u << 3;
inline constexpr std::uint32_t probe2 = 1u << 4;
}  // namespace input

namespace fault {  // AxisFeedback::faults bits
inline constexpr std::uint32_t overtemperature = 1u << 0;  // winding above its limit
inline constexpr std::uint32_t overspeed = 1u << 1;        // motor above 120 % of max speed
inline constexpr std::uint32_t end_stop = 1u << 2;         // load against a hard end stop
inline constexpr std::uint32_t lost_steps = 1u << 3;       // stepper slipped (open loop)
}  // namespace fault

struct AxisFeedback {
  EncoderReading encoder;
  double motor_angle_rad = 0.0;      // continuous
  double motor_velocity_rad_s = 0.0;
  double load_position = 0.0;        // load units (rad or m)
  double load_velocity = 0.0;
  double torque_nm = 0.0;            // actual motor torque (after the current loop)
  double current_a = 0.0;
  double winding_c = 0.0, housing_c = 0.0;
  std::uint32_t inputs = 0;          // input:: bits
  std::uint32_t faults = 0;          // fault:: bits (latched until clear_faults)
  long lost_steps = 0;               // stepper: full steps behind the command
};

class Plant {
public:
  explicit Plant(const PlantDescription& description);  // throws PlantError
  ~Plant();
  Plant(Plant&&) noexcept;
  Plant& operator=(Plant&&) noexcept;
  Plant(const Plant&) = delete;
  Plant& operator=(const Plant&) = delete;

  std::size_t axis_count() const;
  std::optional<std::size_t> axis_index(std::string_view name) const;

  void command(std::size_t axis, const AxisCommand& cmd);
  const AxisFeedback& feedback(std::size_t axis) const;

  // Run whole steps until time() >= t - step (never past t). Returns the number of steps run.
  std::size_t advance_to(Nanos t);
  void step();
  Nanos time() const;
  double step_s() const;

  // Fault injection and test hooks.
  void set_external_load(std::size_t axis, double force);  // added to the load profile
  void set_external_input(std::size_t axis, std::uint32_t input_bits);  // ORed into inputs
  std::uint32_t external_input(std::size_t axis) const;
  // The coil of the holding brake driven from outside the drive (a PLC output wired to it):
  // true = released, false = engaged; nullopt = the drive's AxisCommand::brake_released again.
  void set_brake_control(std::size_t axis, std::optional<bool> released);
  const AxisCommand& last_command(std::size_t axis) const;  // as the drive last gave it
  void clear_faults(std::size_t axis);
  // Machine faults of an axis (axis_faults.hpp); throws PlantError for a load_scale <= 0, values
  // that are not finite, or a scaled load that makes a compliant transmission too stiff for the step.
  // A jam locks the load where it is when the jam begins; an obstacle stops the load on the side it
  // is on when the obstacle appears (fault::end_stop when it reaches it).
  void set_axis_faults(std::size_t axis, const AxisFaults& faults);
  const AxisFaults& axis_faults(std::size_t axis) const;
  // Mechanical energy of the world: kinetic + gravitational + coupling springs (J), evaluated at
  // the half step where ODE's velocities live (see plant.cpp).
  double energy() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdrive::plant
