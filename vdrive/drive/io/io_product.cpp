#include "vdrive/drive/io/io_product.hpp"

namespace vdrive::drive {

IoProduct io_product(const profile::ProductProfile& profile) { return profile.drive.io_rules; }

}  // namespace vdrive::drive
