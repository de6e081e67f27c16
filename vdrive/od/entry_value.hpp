#pragma once
// An integer entry's value from its bytes, and the values an integer type holds: for what reads an
// entry's bytes outside the drive (`vdrive od`, a scenario's SDO read, the web API, signals).
#include <cstdint>
#include <span>

#include "vdrive/od/dictionary.hpp"

namespace vdrive::od {

// The value of little-endian `bytes` (the first 8 at most), sign-extended from their width when
// `entry` has a signed type.
std::int64_t entry_integer(const EntryDesc& entry, std::span<const std::uint8_t> bytes);

struct IntegerRange {
  std::int64_t min = 0, max = 0;
};
// What an integer of `bits` (1-64) holds, as an int64: a 64-bit unsigned type up to INT64_MAX.
IntegerRange integer_range(unsigned bits, bool is_signed);

}  // namespace vdrive::od
