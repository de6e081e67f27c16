#pragma once
// SDO values as the command line writes and prints them: `--type` u8/u16/u32/u64, i8/i16/i32/i64
// (little-endian integers), string (bytes as text), hex (bytes as "01 02 ..").
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vdrive::master {

// Text -> bytes. Integers accept decimal, 0x hex and a sign for i*; throws std::invalid_argument
// naming what was wrong (not a number, out of range for the type, odd hex digits).
std::vector<std::uint8_t> encode_value(std::string_view type, std::string_view text);
// Bytes -> text: "0x0250 (592)" for integers (the bytes' own length when it differs from the
// type), the text for string, "01 02 03" for hex.
std::string decode_value(std::string_view type, const std::vector<std::uint8_t>& bytes);
// The type names accepted above.
const std::vector<std::string>& value_types();

}  // namespace vdrive::master
