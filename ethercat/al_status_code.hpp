#pragma once
// AL Status Code (register 0x0134) values of ETG.1000.6 Table 11 that a slave reports. A product
// may report other codes for the same conditions (its profile's al_codes); these are the standard
// ones the defaults follow.
#include <cstdint>
#include <string_view>

namespace vdrive::ecat::al_status_code {

inline constexpr std::uint16_t kNoError = 0x0000;
inline constexpr std::uint16_t kUnspecifiedError = 0x0001;
inline constexpr std::uint16_t kNoMemory = 0x0002;
inline constexpr std::uint16_t kInvalidStateChange = 0x0011;
inline constexpr std::uint16_t kUnknownState = 0x0012;
inline constexpr std::uint16_t kBootstrapNotSupported = 0x0013;
inline constexpr std::uint16_t kNoValidFirmware = 0x0014;
inline constexpr std::uint16_t kInvalidBootMailboxConfig = 0x0015;
inline constexpr std::uint16_t kInvalidMailboxConfig = 0x0016;
inline constexpr std::uint16_t kInvalidSyncManagerConfig = 0x0017;
inline constexpr std::uint16_t kNoValidInputs = 0x0018;
inline constexpr std::uint16_t kNoValidOutputs = 0x0019;
inline constexpr std::uint16_t kSynchronizationError = 0x001A;
inline constexpr std::uint16_t kSyncManagerWatchdog = 0x001B;
inline constexpr std::uint16_t kInvalidSyncManagerTypes = 0x001C;
inline constexpr std::uint16_t kInvalidOutputConfig = 0x001D;
inline constexpr std::uint16_t kInvalidInputConfig = 0x001E;
inline constexpr std::uint16_t kInvalidWatchdogConfig = 0x001F;
inline constexpr std::uint16_t kNeedsColdStart = 0x0020;
inline constexpr std::uint16_t kNeedsInit = 0x0021;
inline constexpr std::uint16_t kNeedsPreOp = 0x0022;
inline constexpr std::uint16_t kNeedsSafeOp = 0x0023;
inline constexpr std::uint16_t kInvalidInputMapping = 0x0024;
inline constexpr std::uint16_t kInvalidOutputMapping = 0x0025;
inline constexpr std::uint16_t kInconsistentSettings = 0x0026;
inline constexpr std::uint16_t kFreeRunNotSupported = 0x0027;
inline constexpr std::uint16_t kSyncModeNotSupported = 0x0028;
inline constexpr std::uint16_t kFreeRunNeeds3Buffer = 0x0029;
inline constexpr std::uint16_t kBackgroundWatchdog = 0x002A;
inline constexpr std::uint16_t kNoValidInputsAndOutputs = 0x002B;
inline constexpr std::uint16_t kFatalSyncError = 0x002C;
inline constexpr std::uint16_t kNoSyncError = 0x002D;
inline constexpr std::uint16_t kInvalidDcSyncConfig = 0x0030;
inline constexpr std::uint16_t kInvalidDcLatchConfig = 0x0031;
inline constexpr std::uint16_t kPllError = 0x0032;
inline constexpr std::uint16_t kDcSyncIoError = 0x0033;
inline constexpr std::uint16_t kDcSyncTimeout = 0x0034;
inline constexpr std::uint16_t kDcInvalidSyncCycleTime = 0x0035;
inline constexpr std::uint16_t kDcSync0CycleTime = 0x0036;
inline constexpr std::uint16_t kDcSync1CycleTime = 0x0037;
inline constexpr std::uint16_t kEepromNoAccess = 0x0050;
inline constexpr std::uint16_t kEepromError = 0x0051;
inline constexpr std::uint16_t kRestartedLocally = 0x0060;
inline constexpr std::uint16_t kDeviceIdUpdated = 0x0061;
inline constexpr std::uint16_t kVendorSpecificFirst = 0x8000;

// The ETG.1000.6 name of a code, for logs and tool output.
constexpr std::string_view name(std::uint16_t code) {
  switch (code) {
    case kNoError: return "No error";
    case kUnspecifiedError: return "Unspecified error";
    case kNoMemory: return "No memory";
    case kInvalidStateChange: return "Invalid requested state change";
    case kUnknownState: return "Unknown requested state";
    case kBootstrapNotSupported: return "Bootstrap not supported";
    case kNoValidFirmware: return "No valid firmware";
    case kInvalidBootMailboxConfig: return "Invalid mailbox configuration (bootstrap)";
    case kInvalidMailboxConfig: return "Invalid mailbox configuration";
    case kInvalidSyncManagerConfig: return "Invalid sync manager configuration";
    case kNoValidInputs: return "No valid inputs available";
    case kNoValidOutputs: return "No valid outputs";
    case kSynchronizationError: return "Synchronization error";
    case kSyncManagerWatchdog: return "Sync manager watchdog";
    case kInvalidSyncManagerTypes: return "Invalid sync manager types";
    case kInvalidOutputConfig: return "Invalid output configuration";
    case kInvalidInputConfig: return "Invalid input configuration";
    case kInvalidWatchdogConfig: return "Invalid watchdog configuration";
    case kNeedsColdStart: return "Slave needs cold start";
    case kNeedsInit: return "Slave needs Init";
    case kNeedsPreOp: return "Slave needs Pre-Op";
    case kNeedsSafeOp: return "Slave needs Safe-Op";
    case kInvalidInputMapping: return "Invalid input mapping";
    case kInvalidOutputMapping: return "Invalid output mapping";
    case kInconsistentSettings: return "Inconsistent settings";
    case kFreeRunNotSupported: return "Free-run not supported";
    case kSyncModeNotSupported: return "Synchronization not supported";
    case kFreeRunNeeds3Buffer: return "Free-run needs 3-buffer mode";
    case kBackgroundWatchdog: return "Background watchdog";
    case kNoValidInputsAndOutputs: return "No valid inputs and outputs";
    case kFatalSyncError: return "Fatal sync error";
    case kNoSyncError: return "No sync error";
    case kInvalidDcSyncConfig: return "Invalid DC SYNC configuration";
    case kInvalidDcLatchConfig: return "Invalid DC latch configuration";
    case kPllError: return "PLL error";
    case kDcSyncIoError: return "DC sync IO error";
    case kDcSyncTimeout: return "DC sync timeout error";
    case kDcInvalidSyncCycleTime: return "DC invalid sync cycle time";
    case kDcSync0CycleTime: return "DC SYNC0 cycle time";
    case kDcSync1CycleTime: return "DC SYNC1 cycle time";
    case kEepromNoAccess: return "EEPROM no access";
    case kEepromError: return "EEPROM error";
    case kRestartedLocally: return "Slave restarted locally";
    case kDeviceIdUpdated: return "Device identification value updated";
    default: return code >= kVendorSpecificFirst ? "Vendor specific" : "Unknown AL status code";
  }
}

}  // namespace vdrive::ecat::al_status_code
