#pragma once
// Which interface an access comes from. Register permissions and side effects differ per side.
#include <cstdint>

namespace vdrive::esc {

enum class Side : std::uint8_t {
  Ecat,  // EtherCAT frames (the master)
  Pdi,   // process data interface (the slave's microcontroller / firmware)
};

}  // namespace vdrive::esc
