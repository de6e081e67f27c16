#pragma once
// One PDO mapping entry (CiA 301 / ETG.1000.6, the value of 16xxh/1Axxh subindex 01h+): the mapped
// object as (index << 16) | (subindex << 8) | bit length.
#include <cstdint>

namespace vdrive::ecat {

struct PdoMappingEntry {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::uint8_t bits = 0;

  static constexpr PdoMappingEntry decode(std::uint32_t value) {
    return {static_cast<std::uint16_t>(value >> 16), static_cast<std::uint8_t>(value >> 8),
            static_cast<std::uint8_t>(value)};
  }
  static constexpr std::uint32_t encode(std::uint16_t index, std::uint8_t subindex,
                                        std::uint8_t bits) {
    return (static_cast<std::uint32_t>(index) << 16) | (static_cast<std::uint32_t>(subindex) << 8) |
           bits;
  }
  constexpr std::uint32_t encode() const { return encode(index, subindex, bits); }
  // A gap (index 0) or a CiA 301 dummy entry (index = a basic data type 0001h-0007h) occupies
  // bits in the image but moves no object.
  constexpr bool is_gap() const { return index < 0x0008; }

  friend constexpr bool operator==(const PdoMappingEntry&, const PdoMappingEntry&) = default;
};

}  // namespace vdrive::ecat
