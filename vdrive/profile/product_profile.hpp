#pragma once
// A product, as data: everything that makes a slave an A6B, a DS5C1 or a DS1000A-EC rather than
// a generic ESC. Loaded from profiles/<id>/profile.yaml (see profile_loader.hpp). The object
// dictionary comes from profiles/<id>/objects.yaml (later issue).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

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
  std::uint16_t protocols = 0x0004;                  // SII word 0x1C: bit2 CoE, bit3 FoE, ...
};

// Rules the firmware checks for the mailbox SyncManagers at Init->Pre-Op (and Init->Boot).
struct MailboxSmRules {
  std::uint16_t sm0_min_length = 32, sm0_max_length = 0xFFFF;
  std::uint16_t sm1_min_length = 32, sm1_max_length = 0xFFFF;
  std::uint16_t sm0_start_min = 0x1000, sm0_start_max = 0xFFFF;
  std::uint16_t sm1_start_min = 0x1000, sm1_start_max = 0xFFFF;
  std::uint8_t sm0_control_mask = 0x0F, sm0_control_value = 0x06;  // mailbox, write
  std::uint8_t sm1_control_mask = 0x0F, sm1_control_value = 0x02;  // mailbox, read
  bool require_even_start = true;
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

// AL status codes the product reports, by situation. 0 = the product does not report one.
struct AlStatusCodes {
  std::uint16_t invalid_transition = 0x0011;
  std::uint16_t unknown_state = 0x0012;
  std::uint16_t bootstrap_not_supported = 0x0013;
  std::uint16_t invalid_mailbox_config = 0x0016;
  std::uint16_t invalid_boot_mailbox_config = 0x0015;
  // Codes checked at PreOp->SafeOp and in SafeOp/Op (ETG.1000.6 names; products pick their own).
  std::uint16_t sync_watchdog = 0x001B;               // process-data (SM2) watchdog expired
  std::uint16_t invalid_output_config = 0x001D;       // SM2
  std::uint16_t invalid_input_config = 0x001E;        // SM3
  std::uint16_t invalid_watchdog_config = 0x001F;
  std::uint16_t invalid_input_mapping = 0x0024;       // TxPDO
  std::uint16_t invalid_output_mapping = 0x0025;      // RxPDO
  std::uint16_t sync_mode_not_supported = 0x0028;
  std::uint16_t sync_error = 0x002C;                  // SYNC0/IRQ missed
  std::uint16_t no_sync_error = 0x002D;               // sync not locked in time
  std::uint16_t invalid_dc_sync_config = 0x0030;
  std::uint16_t pll_error = 0x0032;
  std::uint16_t invalid_sync_cycle_time = 0x0035;
  std::uint16_t eeprom_error = 0x0051;                // SII EEPROM/identity mismatch
};

// One entry of a default PDO mapping (SII TxPDO/RxPDO categories, 16xxh/1Axxh).
struct PdoEntrySpec {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::uint8_t bit_length = 0;
  std::uint8_t data_type = 0;          // CoE data type code: 0x05 U8, 0x06 U16, 0x07 U32, 0x03 I16...
  std::string name;
};

// A PDO of the default mapping: its mapping object and the SyncManager it is assigned to.
struct PdoSpec {
  std::uint16_t index = 0;             // 0x1600.. (RxPDO) or 0x1A00.. (TxPDO)
  std::string name;
  std::uint8_t sync_manager = 0;       // 2 = outputs, 3 = inputs; 0xFF = not assigned by default
  bool fixed = false;                  // mapping cannot be changed
  std::vector<PdoEntrySpec> entries;
};

struct ProductProfile {
  std::string id;                    // "a6b", "ds5c1", "ds1000a"
  std::string title;                 // human name, e.g. "Panasonic MINAS-A6B"
  Identity identity;
  EscResources esc;
  Mailbox mailbox;
  MailboxSmRules mailbox_rules;
  std::vector<SyncManagerSpec> sync_managers;  // SII SyncManager category, in SM order
  bool has_bootstrap = false;                  // Boot state supported
  // Explicit Device ID (ETG.1000.6): AL control bit5 puts the device ID into AL status code 0x0134
  // and sets AL status bit5. A6B and DS1000A-EC support it, DS5C1 does not.
  bool explicit_device_id = false;
  AlStatusCodes al_codes;
  // SII General category: CoE details (bit0 SDO, 1 SDO info, 2 PDO assign, 3 PDO config,
  // 4 startup upload, 5 complete access), FoE details, ports.
  std::uint8_t coe_details = 0x0F;
  std::uint8_t foe_details = 0;
  // Default PDO mappings (factory values), in object order. Empty when the manual gives none.
  std::vector<PdoSpec> rx_pdos;
  std::vector<PdoSpec> tx_pdos;
};

}  // namespace vdrive::profile
