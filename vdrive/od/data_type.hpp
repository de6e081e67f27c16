#pragma once
// CoE basic data types (ETG.1000.6 / CiA 301 data type indexes) and their sizes.
#include <cstdint>
#include <optional>
#include <string_view>

namespace vdrive::od {

enum class DataType : std::uint16_t {
  Boolean = 0x0001,
  Integer8 = 0x0002,
  Integer16 = 0x0003,
  Integer32 = 0x0004,
  Unsigned8 = 0x0005,
  Unsigned16 = 0x0006,
  Unsigned32 = 0x0007,
  Real32 = 0x0008,
  VisibleString = 0x0009,
  OctetString = 0x000A,
  Integer64 = 0x0015,
  Unsigned64 = 0x001B,
};

// Bits of a fixed-size type; 0 for strings (their size is the entry's bit_length).
std::uint16_t fixed_bit_size(DataType type);
bool is_signed(DataType type);
bool is_string(DataType type);
// "U16", "I32", "VS", "OS", "BOOL", ... as the objects.yaml files spell them.
std::optional<DataType> parse_data_type(std::string_view text);
std::string_view short_name(DataType type);   // "U16"
std::string_view etg_name(DataType type);     // "UINT", "DINT", "STRING(n)" base name for ESI

}  // namespace vdrive::od
