#pragma once
// Which product's I/O rules the drive follows. 60FDh/60FEh and the touch probe are CiA 402
// objects, but their bit layouts, input logic and probe quirks differ per product in ways the
// profile data does not describe; the I/O parts pick the rule set once, at construction.
#include <cstdint>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

enum class IoProduct : std::uint8_t {
  Generic,   // plain CiA 402 / ETG.6010: 60FDh bits 0-2, probe inputs and index only
  A6B,       // Panasonic MINAS-A6B
  DS5C1,     // Xinje DS5C1 (firmware 3791 and later)
  DS1000A,   // DS1000A-EC closed-loop stepper
};

// From ProductProfile::id ("a6b", "ds5c1", "ds1000a"); any other id is Generic.
IoProduct io_product(const profile::ProductProfile& profile);

}  // namespace vdrive::drive
