#pragma once
// ESC register addresses and bit values the master uses (ETG.1000.4 / ET1100 datasheet names).
// Header-only and kept separate from esc_model so ecmaster never links the chip model: a master
// only knows the register map, as a real one does.
#include <cstdint>

namespace vdrive::master::reg {

// ---- information ----------------------------------------------------------------------------
constexpr std::uint16_t kType = 0x0000;             // 1 byte, then revision, build (2)
constexpr std::uint16_t kFmmuCount = 0x0004;        // 1 byte
constexpr std::uint16_t kSmCount = 0x0005;          // 1 byte
constexpr std::uint16_t kRamSize = 0x0006;          // 1 byte, KiB
constexpr std::uint16_t kPortDescriptor = 0x0007;   // 1 byte
constexpr std::uint16_t kFeatures = 0x0008;         // 2 bytes

// ---- station address ----------------------------------------------------------------------
constexpr std::uint16_t kStationAddress = 0x0010;   // configured station address (2)
constexpr std::uint16_t kStationAlias = 0x0012;     // configured station alias (2), from SII word 4

// ---- data link layer ---------------------------------------------------------------------
constexpr std::uint16_t kDlControl = 0x0100;        // 4 bytes
constexpr std::uint16_t kDlControlLoop = 0x0101;    // byte 1: loop control of ports 0-3
constexpr std::uint16_t kDlControlAlias = 0x0103;   // byte 3 bit 0: station alias enable
constexpr std::uint16_t kDlStatus = 0x0110;         // 2 bytes

// ---- application layer -------------------------------------------------------------------
constexpr std::uint16_t kAlControl = 0x0120;        // 2 bytes
constexpr std::uint16_t kAlStatus = 0x0130;         // 2 bytes
constexpr std::uint16_t kAlStatusCode = 0x0134;     // 2 bytes
constexpr std::uint16_t kAlStateMask = 0x000F;
constexpr std::uint16_t kAlErrorFlag = 0x0010;      // in AL status: error indication
constexpr std::uint16_t kAlAcknowledge = 0x0010;    // in AL control: acknowledge error

// ---- interrupts, error counters ----------------------------------------------------------
constexpr std::uint16_t kEcatEventMask = 0x0200;    // 2 bytes
constexpr std::uint16_t kRxErrorCounters = 0x0300;  // 8 bytes: ports 0-3 invalid frame / RX error

// ---- SII EEPROM interface ----------------------------------------------------------------
constexpr std::uint16_t kEepromConfig = 0x0500;     // 1 byte: bit0 offer to PDI, bit1 force ECAT
constexpr std::uint16_t kEepromPdiAccess = 0x0501;  // 1 byte: bit0 PDI has access
constexpr std::uint16_t kEepromControl = 0x0502;    // 2 bytes control/status
constexpr std::uint16_t kEepromAddress = 0x0504;    // 4 bytes, word address
constexpr std::uint16_t kEepromData = 0x0508;       // 4 or 8 bytes
constexpr std::uint8_t kEepromForceEcat = 0x02;
// 0x0502 bits
constexpr std::uint16_t kEepromRead8Bytes = 0x0040;     // 1: a read returns 8 bytes, 0: 4 bytes
constexpr std::uint16_t kEepromCmdRead = 0x0100;
constexpr std::uint16_t kEepromCmdMask = 0x0700;
constexpr std::uint16_t kEepromChecksumError = 0x0800;
constexpr std::uint16_t kEepromLoadError = 0x1000;
constexpr std::uint16_t kEepromAckError = 0x2000;       // missing acknowledge / invalid command
constexpr std::uint16_t kEepromWriteEnableError = 0x4000;
constexpr std::uint16_t kEepromBusy = 0x8000;
constexpr std::uint16_t kEepromErrorBits = kEepromAckError | kEepromWriteEnableError;

// ---- FMMU, SyncManager -------------------------------------------------------------------
constexpr std::uint16_t kFmmu0 = 0x0600;            // 16 bytes per FMMU
constexpr std::uint16_t kFmmuSize = 16;
constexpr std::uint16_t kSm0 = 0x0800;              // 8 bytes per SyncManager
constexpr std::uint16_t kSmSize = 8;
constexpr std::uint16_t kSmActivateOffset = 6;         // activate byte within an SM block
constexpr std::uint8_t kSmControlMailboxWrite = 0x26;  // mailbox, ECAT writes, PDI IRQ on
constexpr std::uint8_t kSmControlMailboxRead = 0x22;   // mailbox, ECAT reads, PDI IRQ on
constexpr std::uint8_t kSmActivateEnable = 0x01;

// ---- distributed clocks ------------------------------------------------------------------
constexpr std::uint16_t kDcSystemTime = 0x0910;     // 8 bytes
constexpr std::uint16_t kDcSpeedCounterStart = 0x0930;
constexpr std::uint16_t kDcTimeFilter = 0x0934;
constexpr std::uint16_t kDcSyncActivation = 0x0981;

}  // namespace vdrive::master::reg
