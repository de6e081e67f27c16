#include "vdrive/od/data_type.hpp"

namespace vdrive::od {

std::uint16_t fixed_bit_size(DataType type) {
  switch (type) {
    case DataType::Boolean: return 1;   // ETG.1000.6: BOOL is one bit in a PDO
    case DataType::Integer8:
    case DataType::Unsigned8: return 8;
    case DataType::Integer16:
    case DataType::Unsigned16: return 16;
    case DataType::Integer32:
    case DataType::Unsigned32:
    case DataType::Real32: return 32;
    case DataType::Integer64:
    case DataType::Unsigned64: return 64;
    case DataType::VisibleString:
    case DataType::OctetString: return 0;
  }
  return 0;
}

bool is_signed(DataType type) {
  return type == DataType::Integer8 || type == DataType::Integer16 ||
         type == DataType::Integer32 || type == DataType::Integer64;
}

bool is_string(DataType type) {
  return type == DataType::VisibleString || type == DataType::OctetString;
}

namespace {
struct Names {
  DataType type;
  std::string_view short_name;
  std::string_view etg_name;
};
// objects.yaml spellings (docs/object-dictionaries.md) and ETG.2000 ESI base type names.
constexpr Names kNames[] = {
    {DataType::Boolean, "BOOL", "BOOL"},          {DataType::Integer8, "I8", "SINT"},
    {DataType::Integer16, "I16", "INT"},          {DataType::Integer32, "I32", "DINT"},
    {DataType::Unsigned8, "U8", "USINT"},         {DataType::Unsigned16, "U16", "UINT"},
    {DataType::Unsigned32, "U32", "UDINT"},       {DataType::Real32, "R32", "REAL"},
    {DataType::VisibleString, "VS", "STRING"},    {DataType::OctetString, "OS", "OCTET_STRING"},
    {DataType::Integer64, "I64", "LINT"},         {DataType::Unsigned64, "U64", "ULINT"},
};
}  // namespace

std::optional<DataType> parse_data_type(std::string_view text) {
  for (const Names& n : kNames)
    if (n.short_name == text) return n.type;
  return std::nullopt;
}

std::string_view short_name(DataType type) {
  for (const Names& n : kNames)
    if (n.type == type) return n.short_name;
  return "?";
}

std::string_view etg_name(DataType type) {
  for (const Names& n : kNames)
    if (n.type == type) return n.etg_name;
  return "?";
}

}  // namespace vdrive::od
