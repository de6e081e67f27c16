#include "vdrive/web/cia402_text.hpp"

#include <fmt/format.h>

namespace vdrive::web {

std::string pds_state_name(std::uint16_t sw) {
  if ((sw & 0x004F) == 0x0000) return "Not ready to switch on";
  if ((sw & 0x004F) == 0x0040) return "Switch on disabled";
  if ((sw & 0x006F) == 0x0021) return "Ready to switch on";
  if ((sw & 0x006F) == 0x0023) return "Switched on";
  if ((sw & 0x006F) == 0x0027) return "Operation enabled";
  if ((sw & 0x006F) == 0x0007) return "Quick stop active";
  if ((sw & 0x004F) == 0x000F) return "Fault reaction active";
  if ((sw & 0x004F) == 0x0008) return "Fault";
  return "?";
}

std::string mode_name(std::int8_t mode) {
  switch (mode) {
    case 0: return "none";
    case 1: return "pp";
    case 2: return "vl";
    case 3: return "pv";
    case 4: return "tq";
    case 6: return "hm";
    case 7: return "ip";
    case 8: return "csp";
    case 9: return "csv";
    case 10: return "cst";
    default: return fmt::format("mode {}", mode);
  }
}

}  // namespace vdrive::web
