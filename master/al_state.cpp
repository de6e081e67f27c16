#include "master/al_state.hpp"

#include <cctype>
#include <string>

namespace vdrive::master {

std::string_view to_string(AlState state) {
  switch (state) {
    case AlState::Init: return "Init";
    case AlState::PreOp: return "Pre-Op";
    case AlState::Boot: return "Boot";
    case AlState::SafeOp: return "Safe-Op";
    case AlState::Op: return "Op";
  }
  return "unknown";
}

std::optional<AlState> parse_al_state(std::string_view text) {
  std::string key;
  for (char c : text) {
    if (c == '-' || c == '_') continue;
    key.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  if (key == "init") return AlState::Init;
  if (key == "preop") return AlState::PreOp;
  if (key == "boot" || key == "bootstrap") return AlState::Boot;
  if (key == "safeop") return AlState::SafeOp;
  if (key == "op") return AlState::Op;
  return std::nullopt;
}

std::string_view al_status_code_text(std::uint16_t code) {
  // ETG.1000.6 Table 11 (the codes a master meets while bringing a line up).
  switch (code) {
    case 0x0000: return "No error";
    case 0x0001: return "Unspecified error";
    case 0x0002: return "No memory";
    case 0x0011: return "Invalid requested state change";
    case 0x0012: return "Unknown requested state";
    case 0x0013: return "Bootstrap not supported";
    case 0x0014: return "No valid firmware";
    case 0x0015: return "Invalid mailbox configuration (bootstrap)";
    case 0x0016: return "Invalid mailbox configuration";
    case 0x0017: return "Invalid sync manager configuration";
    case 0x0018: return "No valid inputs available";
    case 0x0019: return "No valid outputs";
    case 0x001A: return "Synchronization error";
    case 0x001B: return "Sync manager watchdog";
    case 0x001C: return "Invalid sync manager types";
    case 0x001D: return "Invalid output configuration";
    case 0x001E: return "Invalid input configuration";
    case 0x001F: return "Invalid watchdog configuration";
    case 0x0020: return "Slave needs cold start";
    case 0x0021: return "Slave needs Init";
    case 0x0022: return "Slave needs Pre-Op";
    case 0x0023: return "Slave needs Safe-Op";
    case 0x0024: return "Invalid input mapping";
    case 0x0025: return "Invalid output mapping";
    case 0x0026: return "Inconsistent settings";
    case 0x0027: return "Free-run not supported";
    case 0x0028: return "Synchronization not supported";
    case 0x0029: return "Free-run needs 3-buffer mode";
    case 0x002A: return "Background watchdog";
    case 0x002B: return "No valid inputs and outputs";
    case 0x002C: return "Fatal sync error";
    case 0x002D: return "No sync error";
    case 0x0030: return "Invalid DC SYNC configuration";
    case 0x0031: return "Invalid DC latch configuration";
    case 0x0032: return "PLL error";
    case 0x0033: return "DC sync IO error";
    case 0x0034: return "DC sync timeout error";
    case 0x0035: return "DC invalid sync cycle time";
    case 0x0036: return "DC SYNC0 cycle time";
    case 0x0037: return "DC SYNC1 cycle time";
    case 0x0041: return "MBX_AOE";
    case 0x0042: return "MBX_EOE";
    case 0x0043: return "MBX_COE";
    case 0x0044: return "MBX_FOE";
    case 0x0045: return "MBX_SOE";
    case 0x004F: return "MBX_VOE";
    case 0x0050: return "EEPROM no access";
    case 0x0051: return "EEPROM error";
    case 0x0060: return "Slave restarted locally";
    case 0x0061: return "Device identification value updated";
    case 0x00F0: return "Application controller available";
    default: return code >= 0x8000 ? "Vendor specific" : "Unknown AL status code";
  }
}

}  // namespace vdrive::master
