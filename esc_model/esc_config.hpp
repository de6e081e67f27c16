#pragma once
// What distinguishes one ESC instance from another: silicon identity registers, resources and the
// EEPROM contents. Filled from a product profile by vdrive; the chip itself knows nothing of drives.
#include <cstdint>
#include <vector>

namespace vdrive::esc {

struct EscConfig {
  std::uint8_t type = 0x04;               // 0x0000
  std::uint8_t revision = 0x02;           // 0x0001
  std::uint16_t build = 0x0044;           // 0x0002
  std::uint8_t fmmu_count = 3;            // 0x0004, at most 16
  std::uint8_t sm_count = 4;              // 0x0005, at most 16
  std::uint8_t ram_kib = 8;               // 0x0006; process RAM spans 0x1000 .. 0x1000 + ram_kib*1024
  std::uint8_t port_descriptor = 0x0F;    // 0x0007
  std::uint16_t features = 0x018C;        // 0x0008
  std::vector<std::uint8_t> sii_image;    // EEPROM contents, little-endian words; size = EEPROM size
};

}  // namespace vdrive::esc
