#pragma once
// One vendor parameter named by a profile ParameterRef (e.g. A6B Pr1.00 = 3100h, 0.1/s), resolved
// once and read in SI units: raw * scale, or the profile's `fallback` when the product has no such
// object (index 0 / absent) or it reads 0. get(engine_default) is for settings the drive cannot do
// without (loop gains): a reference the profile leaves wholly unset (index 0, fallback 0) reads the
// engine's default instead. Reading is a plain object read.
#include <cstdint>

#include "vdrive/drive/object_ref.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

class ParameterValue {
public:
  ParameterValue(od::ObjectStore& store, const profile::ParameterRef& ref) : ref_(ref) {
    if (ref.index != 0) object_ = ObjectRef<std::int64_t>(store, ref.index, ref.subindex);
  }

  double get() const {
    const std::int64_t raw = object_.get();  // an absent object reads 0
    return raw != 0 ? static_cast<double>(raw) * ref_.scale : ref_.fallback;
  }
  double get(double engine_default) const {
    if (ref_.index == 0 && ref_.fallback == 0.0) return engine_default;
    return get();
  }
  bool present() const { return object_.present(); }

private:
  profile::ParameterRef ref_;
  ObjectRef<std::int64_t> object_;
};

}  // namespace vdrive::drive
