#pragma once
// A typed handle on one object dictionary entry, resolved once (construction may search the
// dictionary) and then read/written by the drive every control step without lookup or allocation.
// An entry the product does not have (e.g. 6075h on the DS1000-EC) gives a handle that reads its
// fallback and ignores writes, so drive code can treat every product alike.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>

#include "vdrive/od/object_store.hpp"

namespace vdrive::drive {

template <typename T>
class ObjectRef {
  static_assert(std::is_integral_v<T>, "object values are integers");

public:
  ObjectRef() = default;
  ObjectRef(od::ObjectStore& store, std::uint16_t index, std::uint8_t subindex = 0, T fallback = T{})
      : store_(&store), entry_(store.dictionary().find(index, subindex)), fallback_(fallback) {
    if (entry_) {
      width_ = std::min<std::size_t>(entry_->value_bytes, sizeof(std::uint64_t));
      signed_ = od::is_signed(entry_->type);
    }
  }

  bool present() const { return entry_ != nullptr; }
  const od::EntryDesc* entry() const { return entry_; }

  // The stored value, sign-extended from the entry's own width (an I16 object read as int32_t
  // keeps its sign; an I8 6060h read as int8_t is exact).
  T get() const {
    if (!entry_) return fallback_;
    const std::uint8_t* bytes = std::as_const(*store_).raw(*entry_).data();
    // Fixed-size copies of the common widths compile to one load (read every control step).
    const std::size_t n = width_;
    std::uint64_t raw = 0;  // little-endian host (x86-64, aarch64)
    switch (n) {
      case 1: raw = bytes[0]; break;
      case 2: { std::uint16_t v; std::memcpy(&v, bytes, 2); raw = v; break; }
      case 4: { std::uint32_t v; std::memcpy(&v, bytes, 4); raw = v; break; }
      case 8: std::memcpy(&raw, bytes, 8); break;
      default: std::memcpy(&raw, bytes, n); break;
    }
    if (n < sizeof(raw) && signed_ && n > 0 && (raw >> (8 * n - 1)) & 1u)
      raw |= ~std::uint64_t{0} << (8 * n);
    return static_cast<T>(raw);
  }

  // Stores `value` truncated to the entry's width (the drive's own objects: no access checks).
  void set(T value) {
    if (!entry_) return;
    std::uint8_t* bytes = store_->raw(*entry_).data();
    const auto raw = static_cast<std::uint64_t>(static_cast<std::int64_t>(value));
    switch (width_) {
      case 1: bytes[0] = static_cast<std::uint8_t>(raw); break;
      case 2: { const auto v = static_cast<std::uint16_t>(raw); std::memcpy(bytes, &v, 2); break; }
      case 4: { const auto v = static_cast<std::uint32_t>(raw); std::memcpy(bytes, &v, 4); break; }
      case 8: std::memcpy(bytes, &raw, 8); break;
      default: std::memcpy(bytes, &raw, width_); break;
    }
  }

private:
  od::ObjectStore* store_ = nullptr;
  const od::EntryDesc* entry_ = nullptr;
  T fallback_{};
  std::size_t width_ = 0;  // bytes of the value taken (entry width, at most 8)
  bool signed_ = false;    // sign-extend from width_
};

}  // namespace vdrive::drive
