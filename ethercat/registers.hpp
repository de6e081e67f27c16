#pragma once
// ESC register map (Beckhoff ET1100/ET1810 class) as named constants and bit layouts.
// Every register address and bit used by the ESC model, the firmware and the tools is named here;
// no magic numbers elsewhere.
#include <cstddef>
#include <cstdint>

namespace vdrive::ecat::reg {

using Addr = std::uint16_t;

// ---- ESC information (read-only, from EscConfig) ------------------------------------------
inline constexpr Addr kType = 0x0000;
inline constexpr Addr kRevision = 0x0001;
inline constexpr Addr kBuild = 0x0002;            // 2 bytes
inline constexpr Addr kFmmusSupported = 0x0004;
inline constexpr Addr kSyncManagersSupported = 0x0005;
inline constexpr Addr kRamSize = 0x0006;          // KiB
inline constexpr Addr kPortDescriptor = 0x0007;
inline constexpr Addr kFeatures = 0x0008;         // 2 bytes

// ---- Station address ----------------------------------------------------------------------
inline constexpr Addr kStationAddress = 0x0010;   // ECAT r/w, PDI r
inline constexpr Addr kStationAlias = 0x0012;     // ECAT r, PDI r/w; loaded from EEPROM word 4

// ---- ESC reset (ET1810): writing 'R','E','S' in sequence resets the ESC ---------------------
inline constexpr Addr kEscResetEcat = 0x0040;
inline constexpr std::uint8_t kResetSequence[3] = {0x52, 0x45, 0x53};

// ---- Data link layer ----------------------------------------------------------------------
inline constexpr Addr kDlControl = 0x0100;        // 4 bytes, ECAT r/w, PDI r
inline constexpr Addr kPhysicalRwOffset = 0x0108; // 2 bytes, ECAT r/w
inline constexpr Addr kDlStatus = 0x0110;         // 2 bytes, read-only

namespace dl_control {
inline constexpr std::uint32_t kForwardingRule = 1u << 0;
inline constexpr int kLoopShift = 8;              // 2 bits per port, ports 0..3
inline constexpr std::uint32_t kFifoSizeMask = 7u << 16;
inline constexpr std::uint32_t kStationAliasEnable = 1u << 24;
inline constexpr std::uint32_t kResetValue = kForwardingRule | kFifoSizeMask;
// Loop setting of one port (bits 8+2p..9+2p).
enum class Loop : std::uint8_t { Auto = 0, AutoClose = 1, Open = 2, Closed = 3 };
}  // namespace dl_control

namespace dl_status {
inline constexpr std::uint16_t kPdiOperational = 1u << 0;     // EEPROM loaded, config area valid
inline constexpr std::uint16_t kPdiWatchdogOk = 1u << 1;      // 0 = PDI watchdog expired
inline constexpr int kLinkShift = 4;                          // physical link, port p = bit 4+p
inline constexpr int kLoopStatusShift = 8;                    // per port: bit 8+2p loop closed,
                                                              //           bit 9+2p communication
}  // namespace dl_status

// ---- Application layer --------------------------------------------------------------------
inline constexpr Addr kAlControl = 0x0120;        // 2 bytes, ECAT r/w, PDI r
inline constexpr Addr kAlStatus = 0x0130;         // 2 bytes, ECAT r, PDI r/w
inline constexpr Addr kAlStatusCode = 0x0134;     // 2 bytes, ECAT r, PDI r/w
inline constexpr Addr kLedOverride = 0x0138;      // 2 bytes, r/w both sides
inline constexpr std::uint16_t kAlStateInit = 0x0001;
inline constexpr std::uint16_t kAlStateMask = 0x001F;  // state (bits 0-3) + error bit 4
inline constexpr std::uint16_t kAlStateBits = 0x000F;  // the state alone
inline constexpr std::uint16_t kAlErrorFlag = 0x0010;  // AL Status bit 4: code in 0x0134

// ---- PDI configuration (read-only, loaded from EEPROM) ------------------------------------
inline constexpr Addr kPdiControl = 0x0140;
inline constexpr Addr kEscConfiguration = 0x0141;
inline constexpr std::uint8_t kEscConfigDeviceEmulation = 1u << 0;
inline constexpr Addr kPdiConfiguration = 0x0150;       // 2 bytes (0x0150, 0x0151 SYNC/LATCH)
inline constexpr Addr kExtendedPdiConfiguration = 0x0152;  // 2 bytes

// ---- Interrupts / events ------------------------------------------------------------------
inline constexpr Addr kEcatEventMask = 0x0200;    // 2 bytes, ECAT r/w, PDI r
inline constexpr Addr kAlEventMask = 0x0204;      // 4 bytes, ECAT r, PDI r/w
inline constexpr std::uint32_t kAlEventMaskReset = 0x00FFFF0F;
inline constexpr Addr kEcatEventRequest = 0x0210; // 2 bytes, read-only
inline constexpr Addr kAlEventRequest = 0x0220;   // 4 bytes, read-only

namespace ecat_event {
inline constexpr std::uint16_t kDcLatch = 1u << 0;
inline constexpr std::uint16_t kDlStatus = 1u << 2;   // cleared by ECAT reading 0x0110
inline constexpr std::uint16_t kAlStatus = 1u << 3;   // cleared by ECAT reading 0x0130
inline constexpr int kSmShift = 4;                    // SM n status mirror: bit 4+n, n < 8
}  // namespace ecat_event

namespace al_event {
inline constexpr std::uint32_t kAlControl = 1u << 0;       // cleared by PDI reading 0x0120
inline constexpr std::uint32_t kDcLatch = 1u << 1;
inline constexpr std::uint32_t kSync0 = 1u << 2;           // cleared by reading 0x098E
inline constexpr std::uint32_t kSync1 = 1u << 3;           // cleared by reading 0x098F
inline constexpr std::uint32_t kSmActivation = 1u << 4;    // cleared by PDI reading 0x08n6
inline constexpr std::uint32_t kEepromEmulation = 1u << 5;
inline constexpr std::uint32_t kPdWatchdog = 1u << 6;      // cleared by PDI reading 0x0440
inline constexpr int kSmShift = 8;                         // SM n interrupt: bit 8+n
}  // namespace al_event

// ---- Error counters -----------------------------------------------------------------------
inline constexpr Addr kRxErrorCounter = 0x0300;   // port p: 0x0300+2p invalid frame, +1 RX error;
                                                  // 0x0308-0x030B forwarded RX errors
inline constexpr Addr kForwardedRxErrorCounter = 0x0308;  // one byte per port
inline constexpr Addr kEcatProcessingErrors = 0x030C;
inline constexpr Addr kErrorCountersLast = kEcatProcessingErrors;  // 0x0300-0x030C: frame errors
inline constexpr Addr kPdiErrors = 0x030D;
inline constexpr Addr kLostLinkCounter = 0x0310;  // 4 bytes, one per port
inline constexpr Addr kLostLinkCounterEnd = 0x0314;
inline constexpr std::uint8_t kCounterMax = 0xFF;  // error and watchdog counters saturate

// ---- Watchdogs ----------------------------------------------------------------------------
inline constexpr Addr kWatchdogDivider = 0x0400;  // 2 bytes, reset 0x09C2 (100 us)
inline constexpr Addr kWatchdogTimePdi = 0x0410;  // 2 bytes, reset 0x03E8
inline constexpr Addr kWatchdogTimeProcessData = 0x0420;  // 2 bytes, reset 0x03E8
inline constexpr Addr kWatchdogStatusProcessData = 0x0440;  // bit0: 1 = active, 0 = expired
inline constexpr Addr kWatchdogCounterProcessData = 0x0442;
inline constexpr Addr kWatchdogCounterPdi = 0x0443;
inline constexpr std::uint16_t kWatchdogDividerReset = 0x09C2;
inline constexpr std::uint16_t kWatchdogTimeReset = 0x03E8;
inline constexpr std::int64_t kWatchdogClockNs = 40;  // 25 MHz base clock

// ---- SII EEPROM interface (delegated to SiiEeprom) -----------------------------------------
inline constexpr Addr kSiiFirst = 0x0500;
inline constexpr Addr kSiiEnd = 0x0510;
inline constexpr Addr kSiiConfig = 0x0500;        // ECAT r/w
inline constexpr Addr kSiiPdiAccess = 0x0501;     // PDI r/w
inline constexpr Addr kSiiControlStatus = 0x0502; // 2 bytes
inline constexpr Addr kSiiAddress = 0x0504;       // 4 bytes, word address
inline constexpr Addr kSiiData = 0x0508;          // 8 bytes (4 on 4-byte-read ESCs)

namespace sii {
// 0x0500
inline constexpr std::uint8_t kOfferToPdi = 1u << 0;
inline constexpr std::uint8_t kForceEcat = 1u << 1;
// 0x0501
inline constexpr std::uint8_t kPdiAccessing = 1u << 0;
// 0x0502-0x0503
inline constexpr std::uint16_t kWriteEnable = 1u << 0;
inline constexpr std::uint16_t kReads8Bytes = 1u << 6;
inline constexpr std::uint16_t kTwoAddressBytes = 1u << 7;
inline constexpr int kCommandShift = 8;
inline constexpr std::uint16_t kCommandMask = 7u << kCommandShift;
inline constexpr std::uint16_t kChecksumError = 1u << 11;
inline constexpr std::uint16_t kDeviceInfoError = 1u << 12;
inline constexpr std::uint16_t kAckError = 1u << 13;
inline constexpr std::uint16_t kWriteEnableError = 1u << 14;
inline constexpr std::uint16_t kBusy = 1u << 15;
}  // namespace sii

// ---- FMMUs --------------------------------------------------------------------------------
inline constexpr Addr kFmmu0 = 0x0600;
inline constexpr Addr kFmmuStride = 16;
inline constexpr int kMaxFmmus = 16;
namespace fmmu {
inline constexpr Addr kLogicalStart = 0x0;   // 4 bytes
inline constexpr Addr kLength = 0x4;         // 2 bytes
inline constexpr Addr kLogicalStartBit = 0x6;
inline constexpr Addr kLogicalStopBit = 0x7;
inline constexpr Addr kPhysicalStart = 0x8;  // 2 bytes
inline constexpr Addr kPhysicalStartBit = 0xA;
inline constexpr Addr kType = 0xB;           // bit0 read, bit1 write
inline constexpr Addr kActivate = 0xC;       // bit0
inline constexpr Addr kUsedBytes = 0xD;      // 0xD-0xF reserved
inline constexpr std::uint8_t kTypeRead = 1u << 0;
inline constexpr std::uint8_t kTypeWrite = 1u << 1;
}  // namespace fmmu

// ---- SyncManagers -------------------------------------------------------------------------
inline constexpr Addr kSm0 = 0x0800;
inline constexpr Addr kSmStride = 8;
inline constexpr int kMaxSyncManagers = 16;
namespace sm {
inline constexpr Addr kStart = 0x0;          // 2 bytes
inline constexpr Addr kLength = 0x2;         // 2 bytes
inline constexpr Addr kControl = 0x4;
inline constexpr Addr kStatus = 0x5;         // read-only
inline constexpr Addr kActivate = 0x6;       // ECAT r/w, PDI r
inline constexpr Addr kPdiControl = 0x7;     // ECAT r, PDI r/w
// Control
inline constexpr std::uint8_t kModeMask = 0x03;
inline constexpr std::uint8_t kModeBuffered = 0x00;
inline constexpr std::uint8_t kModeMailbox = 0x02;
inline constexpr std::uint8_t kDirectionMask = 0x0C;
inline constexpr std::uint8_t kDirectionEcatReads = 0x00;
inline constexpr std::uint8_t kDirectionEcatWrites = 0x04;
inline constexpr std::uint8_t kEcatEventEnable = 1u << 4;
inline constexpr std::uint8_t kAlEventEnable = 1u << 5;
inline constexpr std::uint8_t kWatchdogTrigger = 1u << 6;
// Status
inline constexpr std::uint8_t kIrqWrite = 1u << 0;
inline constexpr std::uint8_t kIrqRead = 1u << 1;
inline constexpr std::uint8_t kMailboxFull = 1u << 3;
inline constexpr int kBufferStateShift = 4;          // 2 bits: last written buffer, 3 = none
inline constexpr std::uint8_t kReadBufferOpen = 1u << 6;
inline constexpr std::uint8_t kWriteBufferOpen = 1u << 7;
// Activate
inline constexpr std::uint8_t kEnable = 1u << 0;
inline constexpr std::uint8_t kRepeatRequest = 1u << 1;
// PDI control
inline constexpr std::uint8_t kPdiDeactivate = 1u << 0;
inline constexpr std::uint8_t kRepeatAck = 1u << 1;
}  // namespace sm

// ---- Distributed clocks (delegated to DcUnit), ET1100 64-bit DC ---------------------------
inline constexpr Addr kDcFirst = 0x0900;
inline constexpr Addr kDcEnd = 0x0A00;
inline constexpr Addr kDcReceiveTimePort0 = 0x0900;  // 4 bytes per port; a frame writing here
                                                     // latches receive times
inline constexpr Addr kDcSystemTime = 0x0910;        // 8 bytes: the local copy of the system time
inline constexpr Addr kDcReceiveTimeEpu = 0x0918;    // 8 bytes: port 0 receive time, 64-bit
inline constexpr Addr kDcSystemTimeOffset = 0x0920;  // 8 bytes
inline constexpr Addr kDcSystemTimeDelay = 0x0928;   // 4 bytes
inline constexpr Addr kDcSystemTimeDifference = 0x092C;  // 4 bytes, bit31 = local copy smaller
inline constexpr Addr kDcSpeedCounterStart = 0x0930;     // 2 bytes
inline constexpr Addr kDcSpeedCounterDiff = 0x0932;      // 2 bytes, signed
inline constexpr Addr kDcDifferenceFilterDepth = 0x0934;
inline constexpr Addr kDcSpeedFilterDepth = 0x0935;
inline constexpr Addr kDcCyclicUnitControl = 0x0980;
inline constexpr Addr kDcActivation = 0x0981;
inline constexpr Addr kDcPulseLength = 0x0982;       // 2 bytes, 10 ns units; 0 = acknowledge mode
inline constexpr Addr kDcActivationStatus = 0x0984;
inline constexpr Addr kDcSync0Status = 0x098E;
inline constexpr Addr kDcSync1Status = 0x098F;
inline constexpr Addr kDcStartTime = 0x0990;         // 8 bytes; read back: next SYNC0 pulse
inline constexpr Addr kDcNextSync0 = kDcStartTime;
inline constexpr Addr kDcNextSync1 = 0x0998;         // 8 bytes
inline constexpr Addr kDcSync0CycleTime = 0x09A0;    // 4 bytes, ns; 0 = single shot
inline constexpr Addr kDcSync1CycleTime = 0x09A4;    // 4 bytes, ns
inline constexpr Addr kDcLatch0Control = 0x09A8;
inline constexpr Addr kDcLatch1Control = 0x09A9;

namespace dc_cyclic_unit_control {  // 0x0980: which side owns the sync out unit and the latches
inline constexpr std::uint8_t kSyncOutPdi = 1u << 0;
inline constexpr std::uint8_t kLatch0Pdi = 1u << 4;
inline constexpr std::uint8_t kLatch1Pdi = 1u << 5;
}  // namespace dc_cyclic_unit_control

namespace dc_activation {  // 0x0981
inline constexpr std::uint8_t kCyclicOperation = 1u << 0;
inline constexpr std::uint8_t kSync0 = 1u << 1;
inline constexpr std::uint8_t kSync1 = 1u << 2;
inline constexpr std::uint8_t kAutoActivation = 1u << 3;     // activate on writing 0x0990
inline constexpr std::uint8_t kStartTimeExtension = 1u << 4; // 32-bit start time -> 64 bit
inline constexpr std::uint8_t kPlausibilityCheck = 1u << 5;
inline constexpr std::uint8_t kNearFuture2s = 1u << 6;
}  // namespace dc_activation

namespace dc_activation_status {  // 0x0984
inline constexpr std::uint8_t kSync0Pending = 1u << 0;
inline constexpr std::uint8_t kSync1Pending = 1u << 1;
inline constexpr std::uint8_t kStartTimeImplausible = 1u << 2;
}  // namespace dc_activation_status

// ---- Digital I/O output data --------------------------------------------------------------
// A digital output device's process-data SyncManager may sit on it (an EL2xxx's SM0 at 0F00h,
// 3-buffered, one byte): the ESC then routes the master's writes through that SyncManager.
inline constexpr Addr kDigitalOutputData = 0x0F00;
inline constexpr Addr kDigitalOutputDataEnd = 0x0F04;

// ---- User RAM ------------------------------------------------------------------------------
inline constexpr Addr kUserRam = 0x0F80;
inline constexpr Addr kRegisterEnd = 0x1000;         // process RAM starts here

// ---- EEPROM words copied into registers on (re)load ----------------------------------------
inline constexpr std::size_t kEepromPdiControlWord = 0;      // -> 0x0140-0x0141
inline constexpr std::size_t kEepromPdiConfigWord = 1;       // -> 0x0150-0x0151
inline constexpr std::size_t kEepromSyncPulseWord = 2;       // -> 0x0982-0x0983
inline constexpr std::size_t kEepromExtPdiConfigWord = 3;    // -> 0x0152-0x0153
inline constexpr std::size_t kEepromAliasWord = 4;           // -> 0x0012-0x0013

}  // namespace vdrive::ecat::reg
