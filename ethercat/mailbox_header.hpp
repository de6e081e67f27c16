#pragma once
// The 6-byte mailbox header of ETG.1000.4/.6 (A6B L4280-L4331) and the mailbox error reply.
//   bytes 0-1 Length   payload bytes after the header
//   bytes 2-3 Address  station address of the source (0 from a master)
//   byte  4   bits 5:0 channel (reserved, 0), bits 7:6 priority
//   byte  5   bits 3:0 type, bits 6:4 counter (1..7, 0 = not counted), bit 7 reserved
#include <cstddef>
#include <cstdint>
#include <span>

#include "ethercat/little_endian.hpp"

namespace vdrive::ecat::mailbox {

inline constexpr std::size_t kHeaderSize = 6;

enum class Type : std::uint8_t {
  Error = 0x0,
  AoE = 0x1,
  EoE = 0x2,
  CoE = 0x3,
  FoE = 0x4,
  SoE = 0x5,
  VoE = 0xF,
};

// ETG.1000.6 mailbox error codes (payload of a type-0 reply: service 0x0001, then the code).
enum class ErrorCode : std::uint16_t {
  Syntax = 0x0001,
  UnsupportedProtocol = 0x0002,
  InvalidChannel = 0x0003,
  ServiceNotSupported = 0x0004,
  InvalidHeader = 0x0005,
  SizeTooShort = 0x0006,
  NoMoreMemory = 0x0007,
  InvalidSize = 0x0008,
};
inline constexpr std::uint16_t kErrorService = 0x0001;
inline constexpr std::size_t kErrorPayloadSize = 4;

struct Header {
  std::uint16_t length = 0;
  std::uint16_t address = 0;
  std::uint8_t channel = 0;
  std::uint8_t priority = 0;
  std::uint8_t type = 0;      // raw 4 bits: may be a type this slave does not know
  std::uint8_t counter = 0;   // 0..7

  // `bytes` holds at least kHeaderSize bytes.
  static constexpr Header decode(std::span<const std::uint8_t> bytes) {
    Header h;
    h.length = get_le16(bytes, 0);
    h.address = get_le16(bytes, 2);
    h.channel = bytes[4] & 0x3F;
    h.priority = static_cast<std::uint8_t>(bytes[4] >> 6);
    h.type = bytes[5] & 0x0F;
    h.counter = (bytes[5] >> 4) & 0x07;
    return h;
  }
  friend constexpr bool operator==(const Header&, const Header&) = default;
  constexpr void encode(std::span<std::uint8_t> bytes) const {
    put_le16(bytes, 0, length);
    put_le16(bytes, 2, address);
    bytes[4] = static_cast<std::uint8_t>((channel & 0x3F) | ((priority & 0x03) << 6));
    bytes[5] = static_cast<std::uint8_t>((type & 0x0F) | ((counter & 0x07) << 4));
  }
};

// The payload of a type-0 (error) reply: service 0x0001, then the code.
constexpr void encode_error_payload(std::span<std::uint8_t> payload, ErrorCode code) {
  put_le16(payload, 0, kErrorService);
  put_le16(payload, 2, static_cast<std::uint16_t>(code));
}

// The slave's reply counter: 1..7, then 1 again (0 is never sent; ETG.1000.4).
constexpr std::uint8_t next_counter(std::uint8_t counter) {
  return counter >= 7 ? 1 : static_cast<std::uint8_t>(counter + 1);
}

}  // namespace vdrive::ecat::mailbox
