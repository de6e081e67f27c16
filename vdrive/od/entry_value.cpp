#include "vdrive/od/entry_value.hpp"

#include <algorithm>
#include <limits>

namespace vdrive::od {

std::int64_t entry_integer(const EntryDesc& entry, std::span<const std::uint8_t> bytes) {
  std::uint64_t raw = 0;
  const std::size_t n = std::min<std::size_t>(bytes.size(), 8);
  for (std::size_t i = 0; i < n; ++i) raw |= static_cast<std::uint64_t>(bytes[i]) << (8 * i);
  if (is_signed(entry.type) && n > 0 && n < 8 && ((raw >> (8 * n - 1)) & 1u)) raw |= ~std::uint64_t{0} << (8 * n);
  return static_cast<std::int64_t>(raw);
}

IntegerRange integer_range(unsigned bits, bool is_signed) {
  if (bits >= 64)
    return {is_signed ? std::numeric_limits<std::int64_t>::min() : 0, std::numeric_limits<std::int64_t>::max()};
  if (is_signed) return {-(std::int64_t{1} << (bits - 1)), (std::int64_t{1} << (bits - 1)) - 1};
  return {0, static_cast<std::int64_t>((std::uint64_t{1} << bits) - 1u)};
}

}  // namespace vdrive::od
