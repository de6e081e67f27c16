#pragma once
// One vendor parameter named by a profile ParameterRef (e.g. A6B Pr1.00 = 3100h, 0.1/s), resolved
// once to an ObjectRef and read in SI units: raw * scale. The profile's rule: `fallback` when the
// product has no such object (index 0 / absent) or it reads 0. A reference the profile leaves
// wholly unset (index 0, fallback 0) reads the caller's engine default instead, so a product whose
// profile does not name the parameter still gets a working value.
#include <cstdint>

#include "vdrive/drive/object_ref.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

class ParameterValue {
public:
  ParameterValue(od::ObjectStore& store, const profile::ParameterRef& ref)
      : ref_(ref), object_(store, ref.index, ref.subindex, 0) {}

  double get(double engine_default) const {
    if (ref_.index == 0) return ref_.fallback != 0.0 ? ref_.fallback : engine_default;
    const std::int64_t raw = object_.get();
    return raw == 0 ? ref_.fallback : static_cast<double>(raw) * ref_.scale;
  }

private:
  profile::ParameterRef ref_;
  ObjectRef<std::int64_t> object_;
};

}  // namespace vdrive::drive
