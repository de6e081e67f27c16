#include "vdrive/esi/esi_names.hpp"

#include <fmt/core.h>

namespace vdrive::esi {

std::string type_name(od::DataType type, std::uint16_t bit_length) {
  using od::DataType;
  switch (type) {
    case DataType::Boolean: return "BOOL";
    case DataType::Integer8: return "SINT";
    case DataType::Integer16: return "INT";
    case DataType::Integer32: return "DINT";
    case DataType::Integer64: return "LINT";
    case DataType::Unsigned8: return "USINT";
    case DataType::Unsigned16: return "UINT";
    case DataType::Unsigned32: return "UDINT";
    case DataType::Unsigned64: return "ULINT";
    case DataType::Real32: return "REAL";
    // Strings carry their capacity in the name (ETG.2000 "STRING(n)", n in bytes).
    case DataType::VisibleString: return fmt::format("STRING({})", bit_length / 8);
    case DataType::OctetString: return fmt::format("OCTET_STRING({})", bit_length / 8);
  }
  return {};
}

std::string type_name(std::uint16_t coe_code, std::uint16_t bit_length) {
  switch (coe_code) {
    case 0x0001: case 0x0002: case 0x0003: case 0x0004: case 0x0005: case 0x0006: case 0x0007:
    case 0x0008: case 0x0009: case 0x000A: case 0x0015: case 0x001B:
      return type_name(static_cast<od::DataType>(coe_code), bit_length);
    default:
      return {};
  }
}

std::string hex(std::uint32_t value, int digits) { return fmt::format("#x{:0{}X}", value, digits); }

std::string hex_binary(std::span<const std::uint8_t> bytes) {
  std::string out;
  out.reserve(bytes.size() * 2);
  for (std::uint8_t b : bytes) out += fmt::format("{:02X}", b);
  return out;
}

}  // namespace vdrive::esi
