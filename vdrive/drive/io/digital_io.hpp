#pragma once
// Digital inputs 60FDh and outputs 60FEh, as each product maps them.
// Inputs: the plant's sensors and the TO/STO input go through the product's input logic
// (InputLogic) and become
//  - the din:: bits the drive acts on, in the user frame: positive_limit is the switch at the end
//    the axis reaches moving in the positive user direction (607Eh position polarity applied);
//  - 60FDh in the product's layout:
//      A6B      bit0 NOT, bit1 POT, bit2 HOME, bit19 EXT1, bit20 EXT2, bit24 INP (L27789-L27906);
//               POT/NOT follow 607Eh (L28993-L29025)
//      DS5C1    bit0 NOT, bit1 POT, bit2 HOME, bit3 TP1, bit4 TP2, bit5 Z held P5-19 ms
//               (firmware 3791+, L4735-L4771, L10201-L10224); terminals, no polarity swap
//      DS1000A  bit0 LM-, bit1 LM+, bit2 ORG, bit3 interlock (TO open), bits16-22 IN1..IN7
//               (L3458-L3478); the plant's probe 1/2 are wired to IN1/IN2
//      Generic  bits 0-2 (CiA 402)
// Outputs: 60FEh-01h under the 60FEh-02h mask. DS1000A-EC: a bit whose mask is 0 keeps its state
// (L3517-L3524), power-on state = 60FEh-01h's initial value, brake engaged (L3507); A6B: a masked
// bit reads 0, except set brake which reads 1 (brake on) (L28090-L28170); others: value & mask.
// update() runs once per control step (profile.drive.control_period_ns); it allocates nothing.
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/io/input_logic.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class DigitalIo {
public:
  explicit DigitalIo(const DriveContext& ctx);

  // Outputs back to their power-on state (call with the store reset to defaults).
  void power_on();

  // plant::input bits and the TO/STO input (true = torque off requested / TO open) -> din:: bits;
  // writes 60FDh and takes over 60FEh. `index_crossed`: the encoder index passed in this step
  // (DS5C1 60FDh bit 5 then stays on for P5-19 ms). din::torque_off only where the product has
  // such an input (profile.drive.torque_off_input).
  std::uint32_t update(std::uint32_t plant_inputs, bool torque_off_input, bool index_crossed);

  // A6B 60FDh bit 24 INP (positioning complete), shown from the next update().
  void set_in_position(bool in_position) { in_position_ = in_position; }

  // profile.drive.brake: Automatic = engaged unless the power stage is on; Master = the set-brake
  // bit (60FEh-01h bit 0) in effect (DS1000A-EC L3480-L3524: engaged until the master unmasks it).
  bool brake_engaged(bool power_stage_on) const;

  // 60FEh-01h bits in effect after the mask, as of the last update()/power_on().
  std::uint32_t outputs() const { return outputs_; }

private:
  std::uint32_t product_layout(std::uint32_t detected, bool swap_limits, bool index_output) const;
  void take_outputs();

  const DriveContext& ctx_;
  InputLogic logic_;
  ObjectRef<std::uint32_t> digital_inputs_, physical_outputs_, output_mask_;
  ObjectRef<std::uint16_t> z_hold_ms_;       // DS5C1 P5-19
  std::uint32_t outputs_ = 0;
  std::int64_t z_remaining_ns_ = 0;
  bool in_position_ = false;
};

}  // namespace vdrive::drive
