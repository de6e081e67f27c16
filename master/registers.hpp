#pragma once
// The project master keeps its own copy of this EtherCAT vocabulary on purpose, written from the
// specification and not shared with ethercat/: it is the independent test oracle of the slave, so a
// wrong value in one is caught by the other.
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
constexpr std::uint16_t kFeatureDc = 0x0004;        // distributed clocks available
constexpr std::uint16_t kFeatureDc64 = 0x0008;      // 64-bit system time

// ---- station address ----------------------------------------------------------------------
constexpr std::uint16_t kStationAddress = 0x0010;   // configured station address (2)
constexpr std::uint16_t kStationAlias = 0x0012;     // configured station alias (2), from SII word 4

// ---- data link layer ---------------------------------------------------------------------
constexpr std::uint16_t kDlControl = 0x0100;        // 4 bytes
constexpr std::uint16_t kDlControlLoop = 0x0101;    // byte 1: loop control of ports 0-3
constexpr std::uint16_t kDlControlAlias = 0x0103;   // byte 3 bit 0: station alias enable
constexpr std::uint16_t kDlStatus = 0x0110;         // 2 bytes
constexpr std::uint16_t kDlStatusPort1Comm = 0x0800; // communication established on port 1

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
constexpr std::uint8_t kFmmuTypeRead = 0x01;           // FMMU type: ECAT reads (inputs)
constexpr std::uint8_t kFmmuTypeWrite = 0x02;          // FMMU type: ECAT writes (outputs)

// ---- distributed clocks ------------------------------------------------------------------
constexpr std::uint16_t kDcReceiveTimes = 0x0900;   // 4 x 4 bytes: port 0-3; a write latches them all
constexpr std::uint16_t kDcSystemTime = 0x0910;     // 8 bytes
constexpr std::uint16_t kDcReceiveTimeUnit = 0x0918;  // 8 bytes: local time of port 0 receive
constexpr std::uint16_t kDcSystemTimeOffset = 0x0920; // 8 bytes
constexpr std::uint16_t kDcSystemTimeDelay = 0x0928;  // 4 bytes
constexpr std::uint16_t kDcSystemTimeDiff = 0x092C;   // 4 bytes: bit 31 sign, 30-0 magnitude
constexpr std::uint16_t kDcCyclicUnitControl = 0x0980;
constexpr std::uint16_t kDcStartTime = 0x0990;        // 8 bytes: first SYNC0 (system time)
constexpr std::uint16_t kDcSync0Cycle = 0x09A0;       // 4 bytes
constexpr std::uint8_t kDcSyncActivateCyclic = 0x01;  // 0x0981 bit 0
constexpr std::uint8_t kDcSyncActivateSync0 = 0x02;   // 0x0981 bit 1
constexpr std::uint16_t kDcSpeedCounterStart = 0x0930;
constexpr std::uint16_t kDcTimeFilter = 0x0934;
constexpr std::uint16_t kDcSyncActivation = 0x0981;

}  // namespace vdrive::master::reg
