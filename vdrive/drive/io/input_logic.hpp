#pragma once
// The product's input logic between the plant's sensors and what the drive firmware detects.
// The plant reports a sensor as 1 while it is actuated, and its sensors are wired the way the
// product's factory settings expect; a setting changed from the factory value therefore changes
// what the drive detects, as on the real machine:
//  - DS1000A-EC: active level of LM+ 215Bh, LM- 215Ch, ORG 2162h (0 active-H, 1 active-L, factory
//    1, L4243-L4261, L4295); set to 0 the drive detects the sensor's idle level as "detected".
//  - A6B: EXT1/EXT2 exist only when assigned to SI5 (3404h) / SI6 (3405h) (L24704-L24706).
//  - DS5C1: touch probe 1/2 inputs exist only when P5-62 / P5-63 name a terminal (L4541-L4548).
// Positions of the bits are plant::input's (physical frame: positive_limit is at the motor's
// positive end); din::torque_off (the TO/STO input is open) passes through unchanged.
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/io/io_product.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class InputLogic {
public:
  explicit InputLogic(const DriveContext& ctx);

  IoProduct product() const { return product_; }

  // plant::input bits (| din::torque_off) -> the same bits as the firmware detects them.
  std::uint32_t detected(std::uint32_t plant_inputs) const;

  // The external probe input of touch-probe channel 1 or 2 is assigned to a terminal.
  bool probe_assigned(int channel) const;

private:
  IoProduct product_;
  ObjectRef<std::uint16_t> positive_limit_logic_, negative_limit_logic_, home_logic_;  // DS1000A-EC
  ObjectRef<std::int32_t> probe1_terminal_, probe2_terminal_;  // A6B 3404h/3405h, DS5C1 253Eh/253Fh
};

}  // namespace vdrive::drive
