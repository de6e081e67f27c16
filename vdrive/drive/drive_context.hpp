#pragma once
// What every part of the drive engine is built with: the product, its object dictionary values
// and the unit scaling in force. Parts resolve their ObjectRefs from `objects` at construction.
#include "vdrive/drive/unit_scaling.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

struct DriveContext {
  const profile::ProductProfile& profile;
  od::ObjectStore& objects;
  const UnitScaling& units;
};

}  // namespace vdrive::drive
