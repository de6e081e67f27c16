#pragma once
// CiA 402 words in words, for the page: the PDS state a statusword shows (CiA 402-2 Table 30) and
// the name of a mode of operation (6060h/6061h).
#include <cstdint>
#include <string>

namespace vdrive::web {

// "Switch on disabled", "Operation enabled", "Fault", ...; "?" for a pattern no state has.
std::string pds_state_name(std::uint16_t statusword);
// "csp", "pp", ...; "none" for 0; "mode -1" for a manufacturer's mode.
std::string mode_name(std::int8_t mode);

}  // namespace vdrive::web
