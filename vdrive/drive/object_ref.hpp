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
      : store_(&store), entry_(store.dictionary().find(index, subindex)), fallback_(fallback) {}

  bool present() const { return entry_ != nullptr; }
  const od::EntryDesc* entry() const { return entry_; }

  // The stored value, sign-extended from the entry's own width (an I16 object read as int32_t
  // keeps its sign; an I8 6060h read as int8_t is exact).
  T get() const {
    if (!entry_) return fallback_;
    const std::span<const std::uint8_t> bytes = std::as_const(*store_).raw(*entry_);
    std::uint64_t raw = 0;
    const std::size_t n = std::min<std::size_t>(bytes.size(), sizeof(raw));
    std::memcpy(&raw, bytes.data(), n);  // little-endian host (x86-64, aarch64)
    if (n < sizeof(raw) && is_signed_entry() && n > 0 && (raw >> (8 * n - 1)) & 1u)
      raw |= ~std::uint64_t{0} << (8 * n);
    return static_cast<T>(raw);
  }

  // Stores `value` truncated to the entry's width (the drive's own objects: no access checks).
  void set(T value) {
    if (!entry_) return;
    const std::span<std::uint8_t> bytes = store_->raw(*entry_);
    const auto raw = static_cast<std::uint64_t>(static_cast<std::int64_t>(value));
    std::memcpy(bytes.data(), &raw, std::min<std::size_t>(bytes.size(), sizeof(raw)));
  }

private:
  bool is_signed_entry() const { return od::is_signed(entry_->type); }

  od::ObjectStore* store_ = nullptr;
  const od::EntryDesc* entry_ = nullptr;
  T fallback_{};
};

}  // namespace vdrive::drive
