#include "vdrive/drive/io/io_product.hpp"

namespace vdrive::drive {

IoProduct io_product(const profile::ProductProfile& profile) {
  if (profile.id == "a6b") return IoProduct::A6B;
  if (profile.id == "ds5c1") return IoProduct::DS5C1;
  if (profile.id == "ds1000a") return IoProduct::DS1000A;
  return IoProduct::Generic;
}

}  // namespace vdrive::drive
