#pragma once
// The ESC side of a product: identity, SyncManagers and mailbox as its SII/ESI declares them, the
// mailbox SyncManager rules, the ESC's resources, and the AL status codes it reports.
#include <cstdint>
#include <optional>
#include <string>

#include "ethercat/al_status_code.hpp"
#include "ethercat/sii.hpp"

namespace vdrive::profile {

struct Identity {
  std::uint32_t vendor_id = 0;
  std::uint32_t product_code = 0;
  std::uint32_t revision = 0;
  std::uint32_t serial = 0;
  std::uint32_t device_type = 0;      // 1000h
  std::string device_name;            // 1008h and SII device name string
  std::string hardware_version;       // 1009h
  std::string software_version;       // 100Ah
  std::string vendor_name;            // SII/ESI vendor string
  std::string order_code;             // SII order string (ESI Type)
  std::string group;                  // SII group string (ESI group type)
  // The product codes the product stands for: those equal to product_code in the bits of this mask
  // (the A6B: bits 31-28 = 6 for the whole series). A network may serve any of them (an ENI's own
  // product code and revision), with the product's behaviour.
  std::uint32_t product_code_mask = 0xFFFFFFFF;

  bool covers(std::uint32_t vendor, std::uint32_t code) const {
    return vendor == vendor_id && (code & product_code_mask) == (product_code & product_code_mask);
  }
};

// One SyncManager as the product's SII/ESI declares it (default start, length, control, enable).
struct SyncManagerSpec {
  std::uint16_t start = 0;
  std::uint16_t length = 0;
  std::uint8_t control = 0;
  bool enable = true;
  enum class Kind : std::uint8_t { MailboxOut = 1, MailboxIn = 2, Outputs = 3, Inputs = 4 } kind{};
};

struct Mailbox {
  std::uint16_t rx_offset = 0x1000, rx_size = 0x80;   // master -> slave (SM0)
  std::uint16_t tx_offset = 0x1080, tx_size = 0x80;   // slave -> master (SM1)
  std::optional<std::uint16_t> boot_rx_offset, boot_rx_size, boot_tx_offset, boot_tx_size;
  std::uint16_t protocols = ecat::sii::mailbox_protocol::kCoE;  // SII word 0x1C
};

// Rules the firmware checks for the mailbox SyncManagers at Init->Pre-Op (and Init->Boot).
struct MailboxSmRules {
  std::uint16_t sm0_min_length = 32, sm0_max_length = 0xFFFF;
  std::uint16_t sm1_min_length = 32, sm1_max_length = 0xFFFF;
  std::uint16_t sm0_start_min = 0x1000, sm0_start_max = 0xFFFF;
  std::uint16_t sm1_start_min = 0x1000, sm1_start_max = 0xFFFF;
  std::uint8_t sm0_control_mask = 0x0F, sm0_control_value = 0x06;  // mailbox, write
  std::uint8_t sm1_control_mask = 0x0F, sm1_control_value = 0x02;  // mailbox, read
  bool require_even_start = true;            // SM0 (receive mailbox) start must be even
  bool require_even_sm1_start = true;        // SM1 (send mailbox) too (profile key, default as SM0)
};

struct EscResources {
  std::uint8_t type = 0x04, revision = 0x02;
  std::uint16_t build = 0x0044;
  std::uint8_t fmmu_count = 3, sm_count = 4, ram_kib = 8, port_descriptor = 0x0F;
  std::uint16_t features = 0x018C;
  std::uint16_t eeprom_bytes = 2048;                 // SII word 0x3E: (kbit) - 1
  std::uint16_t pdi_control = 0x0C05, pdi_config = 0x6603, sync_pulse_length = 0x0064;
  std::uint16_t extended_pdi_config = 0, station_alias = 0;
};

// AL status codes the product reports, by situation: ETG.1000.6's code unless profile.yaml names the
// product's own. 0 = the product does not report one.
struct AlStatusCodes {
  std::uint16_t invalid_transition = ecat::al_status_code::kInvalidStateChange;
  std::uint16_t unknown_state = ecat::al_status_code::kUnknownState;
  std::uint16_t bootstrap_not_supported = ecat::al_status_code::kBootstrapNotSupported;
  std::uint16_t invalid_mailbox_config = ecat::al_status_code::kInvalidMailboxConfig;
  std::uint16_t invalid_boot_mailbox_config = ecat::al_status_code::kInvalidBootMailboxConfig;
  // Codes checked at PreOp->SafeOp and in SafeOp/Op (ETG.1000.6 names; products pick their own).
  std::uint16_t sync_watchdog = ecat::al_status_code::kSyncManagerWatchdog;  // process-data (SM2) watchdog expired
  std::uint16_t invalid_output_config = ecat::al_status_code::kInvalidOutputConfig;  // SM2
  std::uint16_t invalid_input_config = ecat::al_status_code::kInvalidInputConfig;  // SM3
  std::uint16_t invalid_watchdog_config = ecat::al_status_code::kInvalidWatchdogConfig;
  std::uint16_t invalid_input_mapping = ecat::al_status_code::kInvalidInputMapping;  // TxPDO
  std::uint16_t invalid_output_mapping = ecat::al_status_code::kInvalidOutputMapping;  // RxPDO
  std::uint16_t sync_mode_not_supported = ecat::al_status_code::kSyncModeNotSupported;
  std::uint16_t sync_error = ecat::al_status_code::kFatalSyncError;  // SYNC0/IRQ missed
  std::uint16_t no_sync_error = ecat::al_status_code::kNoSyncError;  // sync not locked in time
  std::uint16_t invalid_dc_sync_config = ecat::al_status_code::kInvalidDcSyncConfig;
  std::uint16_t pll_error = ecat::al_status_code::kPllError;
  std::uint16_t invalid_sync_cycle_time = ecat::al_status_code::kDcInvalidSyncCycleTime;
  std::uint16_t eeprom_error = ecat::al_status_code::kEepromError;  // SII EEPROM/identity mismatch
};

// When the firmware checks its SII EEPROM and reports AL status code `eeprom_error` (profile.yaml
// `sii_check`; absent: never). The ESC's EEPROM status 0x0502 is read over the PDI; the identity
// words are read from the EEPROM chip as the drive's microcontroller reads them at start-up.
struct SiiCheck {
  bool enabled = false;
  // 0x0502 bits that count as an EEPROM error (bit 11 checksum, 12 device information not loaded,
  // 13 acknowledge/command error, 14 write enable error).
  std::uint16_t error_bits = 0;
  // At power-on: SII words 8-13 (vendor, product code, revision) against 1018h:01-03.
  bool identity = false;
  // The error bits in every state, whenever the firmware runs (A6B Err85.3 "全部 ESM"); false: at
  // Init->PreOp only (ETG slave stack code: EEPROM not loaded -> 0x0051, the slave stays in Init).
  bool every_state = false;
  // false: the error cannot be acknowledged; only a power cycle clears it (A6B: 不可清零).
  bool clearable = true;
};

}  // namespace vdrive::profile
