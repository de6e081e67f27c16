#pragma once
// A vendor parameter (profile ParameterRef) read as an SI value: raw * scale, or the fallback when
// the product has no such object or it reads 0. Resolved once; get() is a plain object read.
#include <cstdint>

#include "vdrive/drive/object_ref.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

class ParameterValue {
public:
  ParameterValue(od::ObjectStore& store, const profile::ParameterRef& ref)
      : scale_(ref.scale), fallback_(ref.fallback) {
    if (ref.index != 0) object_ = ObjectRef<std::int64_t>(store, ref.index, ref.subindex);
  }

  double get() const {
    const std::int64_t raw = object_.get();   // an absent object reads 0
    return raw != 0 ? static_cast<double>(raw) * scale_ : fallback_;
  }
  bool present() const { return object_.present(); }

private:
  ObjectRef<std::int64_t> object_;
  double scale_ = 1.0;
  double fallback_ = 0.0;
};

}  // namespace vdrive::drive
