#pragma once
// The project master keeps its own copy of this EtherCAT vocabulary on purpose, written from the
// specification and not shared with ethercat/: it is the independent test oracle of the slave, so a
// wrong value in one is caught by the other.
// EtherCAT application-layer states (AL control 0x0120 / AL status 0x0130 low nibble).
#include <cstdint>
#include <optional>
#include <string_view>

namespace vdrive::master {

enum class AlState : std::uint8_t { Init = 0x01, PreOp = 0x02, Boot = 0x03, SafeOp = 0x04, Op = 0x08 };

// "Init", "Pre-Op", "Boot", "Safe-Op", "Op"; "0x0N?" style text for values that are no state.
std::string_view to_string(AlState state);
// Parses "init", "preop", "boot", "safeop", "op" (case-insensitive, '-' and '_' ignored).
std::optional<AlState> parse_al_state(std::string_view text);

// What AL status reported: the state nibble, the error flag and, when set, the AL status code.
struct AlStatus {
  std::uint8_t state = 0;            // raw low nibble of 0x0130
  bool error = false;                // 0x0130 bit 4
  std::uint16_t status_code = 0;     // 0x0134
};

// ETG.1000.6 Table 11 text for an AL status code ("Invalid mailbox configuration", ...).
std::string_view al_status_code_text(std::uint16_t code);

}  // namespace vdrive::master
