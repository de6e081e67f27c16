#pragma once
// The contents of the SII EEPROM (ETG.1000.6 5.4, ETG.2010): word addresses of the fixed area,
// category types, and the codes and flags inside them. The register window the master reads it
// through (0x0500-0x050F) is in registers.hpp.
#include <cstdint>

namespace vdrive::ecat::sii {

// ---- Fixed area (words 0x00-0x3F) -------------------------------------------------------------
inline constexpr std::uint16_t kWordConfigChecksum = 0x07;   // low byte: CRC-8 of words 0-6
inline constexpr std::uint16_t kWordVendorId = 0x08;         // 2 words each from here
inline constexpr std::uint16_t kWordProductCode = 0x0A;
inline constexpr std::uint16_t kWordRevision = 0x0C;
inline constexpr std::uint16_t kWordSerial = 0x0E;
inline constexpr std::uint16_t kWordBootRxMailbox = 0x14;    // offset, size; then the Tx mailbox
inline constexpr std::uint16_t kWordStdRxMailbox = 0x18;
inline constexpr std::uint16_t kWordMailboxProtocols = 0x1C;
inline constexpr std::uint16_t kWordEepromSize = 0x3E;        // (kbit) - 1
inline constexpr std::uint16_t kWordVersion = 0x3F;
inline constexpr std::uint16_t kWordFirstCategory = 0x40;

// Word 0x1C: the mailbox protocols the slave supports.
namespace mailbox_protocol {
inline constexpr std::uint16_t kAoE = 1u << 0;
inline constexpr std::uint16_t kEoE = 1u << 1;
inline constexpr std::uint16_t kCoE = 1u << 2;
inline constexpr std::uint16_t kFoE = 1u << 3;
inline constexpr std::uint16_t kSoE = 1u << 4;
inline constexpr std::uint16_t kVoE = 1u << 5;
}  // namespace mailbox_protocol

// ---- Categories (ETG.1000.6 Table 19) ---------------------------------------------------------
enum class Category : std::uint16_t {
  Strings = 10,
  General = 30,
  Fmmu = 40,
  SyncManager = 41,
  TxPdo = 50,
  RxPdo = 51,
  End = 0xFFFF,
};

// FMMU category: one usage byte per FMMU (ETG.1000.6 Table 23).
namespace fmmu_usage {
inline constexpr std::uint8_t kUnused = 0;
inline constexpr std::uint8_t kOutputs = 1;
inline constexpr std::uint8_t kInputs = 2;
inline constexpr std::uint8_t kMailboxState = 3;
}  // namespace fmmu_usage

// General category, byte 0x0B (ETG.2010): the Explicit Device ID is reported in AL status code 0x0134.
inline constexpr std::uint8_t kGeneralFlagIdentAlStatus = 0x08;

// TxPDO/RxPDO categories, PDO flags (ETG.2010): in the default assignment; content fixed.
inline constexpr std::uint16_t kPdoFlagDefault = 0x0002;
inline constexpr std::uint16_t kPdoFlagFixedContent = 0x0010;

}  // namespace vdrive::ecat::sii
