#pragma once
// ETG.2000 spellings used in ESI files: data type names, hex numbers, hex binary.
#include <cstdint>
#include <span>
#include <string>

#include "vdrive/od/data_type.hpp"

namespace vdrive::esi {

// "UINT", "DINT", "STRING(16)", "OCTET_STRING(4)" ... for a type of `bit_length` bits (the
// length matters only for strings). Unknown CoE codes give "" (caller decides).
std::string type_name(od::DataType type, std::uint16_t bit_length);
// The same for a CoE data type code as the PDO entries of a profile carry it (0x0006 = UINT).
std::string type_name(std::uint16_t coe_code, std::uint16_t bit_length);

// ESI HexDecValue: "#x" and the value in upper-case hex, zero-padded to `digits`.
std::string hex(std::uint32_t value, int digits);
// ESI HexBinary: bytes in the order given, two upper-case hex digits each ("0C050366").
std::string hex_binary(std::span<const std::uint8_t> bytes);

}  // namespace vdrive::esi
