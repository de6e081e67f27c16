#pragma once
// Which product's I/O rules the drive follows. 60FDh/60FEh and the touch probe are CiA 402
// objects, but their bit layouts, input logic and probe quirks differ per product in ways the
// object data does not describe; the product names its rule set (drive.io_rules) and the I/O parts
// take it once, at construction.
#include <cstdint>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

// Generic (plain CiA 402 / ETG.6010), A6B, DS5C1, DS1000A: see profile::IoRuleSet.
using IoProduct = profile::IoRuleSet;

IoProduct io_product(const profile::ProductProfile& profile);

}  // namespace vdrive::drive
