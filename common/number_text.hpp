#pragma once
// Whole numbers as users write them in files and on command lines: decimal, or hex after 0x/0X.
#include <cstdint>
#include <optional>
#include <string_view>

namespace vdrive {

// The value, or nullopt for empty text, other characters, or more than 64 bits.
std::optional<std::uint64_t> parse_unsigned(std::string_view text);

}  // namespace vdrive
