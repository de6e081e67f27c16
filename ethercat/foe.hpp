#pragma once
// FoE on the wire (ETG.1000.6 5.7, File Access over EtherCAT). Offsets are into the mailbox
// payload (after the 6-byte mailbox header); fields are little-endian:
//
//   byte 0     OpCode: 1 RRQ, 2 WRQ, 3 DATA, 4 ACK, 5 ERR, 6 BUSY
//   byte 1     reserved (0)
//   bytes 2-5  RRQ/WRQ: password; DATA/ACK: packet number; ERR: error code;
//              BUSY: done (2 bytes) + entire (2 bytes)
//   bytes 6-   RRQ/WRQ: file name; DATA: file data; ERR: error text (optional)
//
// A DATA packet carries at most (mailbox size - 12) bytes (6 mailbox header + 6 FoE header); a
// shorter one is the last of the file (an empty one ends a file of whole packets).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "ethercat/little_endian.hpp"

namespace vdrive::ecat::foe {

enum class OpCode : std::uint8_t {
  ReadRequest = 1,
  WriteRequest = 2,
  Data = 3,
  Ack = 4,
  Error = 5,
  Busy = 6,
};

inline constexpr std::size_t kHeaderSize = 6;              // opcode, reserved, 4-byte field
inline constexpr std::size_t kField = 2;                   // password / packet / error code
inline constexpr std::size_t kBusyDoneAt = 2, kBusyEntireAt = 4;  // BUSY: 2 bytes each
inline constexpr std::size_t kData = kHeaderSize;          // file name / data / error text
inline constexpr std::size_t kMailboxOverhead = 6 + kHeaderSize;  // what a DATA packet loses

constexpr OpCode opcode_of(std::span<const std::uint8_t> payload) {
  return static_cast<OpCode>(payload[0]);
}
// The 6-byte header: opcode, reserved 0, the 4-byte field.
constexpr void put_header(std::span<std::uint8_t> payload, OpCode op, std::uint32_t field) {
  payload[0] = static_cast<std::uint8_t>(op);
  payload[1] = 0;
  put_le32(payload, kField, field);
}
constexpr std::uint32_t field_of(std::span<const std::uint8_t> payload) {
  return get_le32(payload, kField);
}

// ETG.1000.6 Table "FoE error codes" with the meanings the ETG slave stack code gives them
// (SSC ecatfoe.h): 0x8008 = a file that may only be written in Bootstrap, 0x8009 = a file that
// may not be written in Bootstrap.
enum class ErrorCode : std::uint32_t {
  NotDefined = 0x8000,
  NotFound = 0x8001,
  AccessDenied = 0x8002,
  DiskFull = 0x8003,
  Illegal = 0x8004,
  PacketNumberWrong = 0x8005,
  AlreadyExists = 0x8006,
  NoUser = 0x8007,
  BootstrapOnly = 0x8008,
  NotBootstrap = 0x8009,
  NoRights = 0x800A,
  ProgramError = 0x800B,
  ChecksumError = 0x800C,
  FirmwareDoesNotFit = 0x800D,
  NoFileToRead = 0x800F,
};

// The error text sent with an ERR reply (ETG.1000.6 names).
constexpr std::string_view error_text(ErrorCode code) {
  switch (code) {
    case ErrorCode::NotDefined: return "Not defined";
    case ErrorCode::NotFound: return "Not found";
    case ErrorCode::AccessDenied: return "Access denied";
    case ErrorCode::DiskFull: return "Disk full";
    case ErrorCode::Illegal: return "Illegal";
    case ErrorCode::PacketNumberWrong: return "Packet number wrong";
    case ErrorCode::AlreadyExists: return "Already exists";
    case ErrorCode::NoUser: return "No user";
    case ErrorCode::BootstrapOnly: return "Bootstrap only";
    case ErrorCode::NotBootstrap: return "Not Bootstrap";
    case ErrorCode::NoRights: return "No rights";
    case ErrorCode::ProgramError: return "Program error";
    case ErrorCode::ChecksumError: return "Checksum error";
    case ErrorCode::FirmwareDoesNotFit: return "Firmware does not fit for hardware";
    case ErrorCode::NoFileToRead: return "No file to read";
  }
  return "Not defined";
}

}  // namespace vdrive::ecat::foe
