#pragma once
// EtherCAT application-layer states and the bit layout of AL Control (0x0120) and AL Status
// (0x0130), as ETG.1000.6 defines them and the Beckhoff ESC datasheets document them.
#include <cstdint>
#include <string_view>

namespace vdrive::ecat {

// The value in bits 3:0 of AL Control / AL Status.
enum class AlState : std::uint8_t {
  Init = 0x1,
  PreOp = 0x2,
  Boot = 0x3,
  SafeOp = 0x4,
  Op = 0x8,
};

// True for the five values ETG.1000.6 defines; anything else is an "unknown requested state".
constexpr bool is_defined_state(std::uint8_t value) {
  return value == 0x1 || value == 0x2 || value == 0x3 || value == 0x4 || value == 0x8;
}

// Rank in the Init < PreOp < SafeOp < Op ladder. Boot sits beside PreOp, reached only from Init,
// so it ranks with PreOp: leaving Boot for Init is "going down".
constexpr int rank(AlState s) {
  switch (s) {
    case AlState::Init: return 0;
    case AlState::PreOp: return 1;
    case AlState::Boot: return 1;
    case AlState::SafeOp: return 2;
    case AlState::Op: return 3;
  }
  return 0;
}

constexpr std::string_view name(AlState s) {
  switch (s) {
    case AlState::Init: return "Init";
    case AlState::PreOp: return "PreOp";
    case AlState::Boot: return "Boot";
    case AlState::SafeOp: return "SafeOp";
    case AlState::Op: return "Op";
  }
  return "?";
}

// AL Control 0x0120 (written by the master, read by the firmware).
struct AlControl {
  static constexpr std::uint16_t kStateMask = 0x000F;
  static constexpr std::uint16_t kErrorAck = 0x0010;   // bit4 Error Ind Ack
  static constexpr std::uint16_t kIdRequest = 0x0020;  // bit5 Explicit Device ID request

  std::uint8_t requested = 0;  // raw bits 3:0, may be an undefined value
  bool error_ack = false;
  bool id_request = false;

  static constexpr AlControl decode(std::uint16_t raw) {
    return AlControl{static_cast<std::uint8_t>(raw & kStateMask), (raw & kErrorAck) != 0,
                     (raw & kIdRequest) != 0};
  }
};

// AL Status 0x0130 (written by the firmware, read by the master).
struct AlStatusBits {
  static constexpr std::uint16_t kErrorInd = 0x0010;   // bit4: error, code in 0x0134
  static constexpr std::uint16_t kIdLoaded = 0x0020;   // bit5: device ID in 0x0134

  static constexpr std::uint16_t encode(AlState state, bool error, bool id_loaded) {
    return static_cast<std::uint16_t>(static_cast<std::uint16_t>(state) | (error ? kErrorInd : 0) |
                                      (id_loaded ? kIdLoaded : 0));
  }
};

}  // namespace vdrive::ecat
