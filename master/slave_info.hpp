#pragma once
// What a slave's SII EEPROM says about it (ETG.1000.6 Table 16 / ETG.2010): identity, mailbox,
// and the categories Strings, General, FMMU, SyncManager, TxPDO/RxPDO.
#include <cstdint>
#include <string>
#include <vector>

namespace vdrive::master {

// SII word 0x1C bits.
namespace mailbox_protocol {
constexpr std::uint16_t kAoE = 0x0001, kEoE = 0x0002, kCoE = 0x0004, kFoE = 0x0008, kSoE = 0x0010,
                        kVoE = 0x0020;
}

struct SiiSyncManager {       // SyncManager category (41), 8 bytes each
  std::uint16_t start = 0;
  std::uint16_t length = 0;
  std::uint8_t control = 0;
  std::uint8_t enable = 0;    // bit 0: enabled
  std::uint8_t type = 0;      // 0 unused, 1 mailbox out, 2 mailbox in, 3 outputs, 4 inputs
};

struct SiiPdoEntry {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::uint8_t data_type = 0;
  std::uint8_t bit_length = 0;
  std::string name;
};

struct SiiPdo {               // TxPDO (50) / RxPDO (51) category entries
  std::uint16_t index = 0;
  std::uint8_t sync_manager = 0;
  std::string name;
  std::vector<SiiPdoEntry> entries;
};

struct SlaveInfo {
  // Identity (words 0x08-0x0F).
  std::uint32_t vendor_id = 0;
  std::uint32_t product_code = 0;
  std::uint32_t revision = 0;
  std::uint32_t serial = 0;
  std::uint16_t alias = 0;              // word 0x04
  // Standard mailbox (words 0x18-0x1C), bootstrap mailbox (0x14-0x17).
  std::uint16_t mailbox_rx_offset = 0, mailbox_rx_size = 0;
  std::uint16_t mailbox_tx_offset = 0, mailbox_tx_size = 0;
  std::uint16_t boot_rx_offset = 0, boot_rx_size = 0;
  std::uint16_t boot_tx_offset = 0, boot_tx_size = 0;
  std::uint16_t mailbox_protocols = 0;
  std::uint16_t eeprom_kbit = 0;        // word 0x3E + 1
  // Strings category (10); General category (30) refers to it by 1-based index.
  std::vector<std::string> strings;
  std::string name;                     // General: name string (device name)
  std::string group;                    // General: group string
  std::string order;                    // General: order number string
  std::uint8_t coe_details = 0, foe_details = 0, eoe_details = 0;
  bool has_general = false;
  std::vector<std::uint8_t> fmmus;      // FMMU category (40): 0 unused, 1 outputs, 2 inputs, 3 SM status
  std::vector<SiiSyncManager> sync_managers;
  std::vector<SiiPdo> tx_pdos, rx_pdos;

  bool has_mailbox() const { return mailbox_rx_size != 0 && mailbox_tx_size != 0; }
};

}  // namespace vdrive::master
