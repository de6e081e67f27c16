#pragma once
// One <Device> of an EtherCAT Slave Information file (EtherCATInfo XML, ETG.2000) as read, before
// it becomes a product (esi_import.hpp): the identity, the ESC's SyncManagers, FMMUs and EEPROM,
// the PDOs, the mailbox and its protocols, the DC op modes and the object dictionary. Numbers are
// as the file gives them; `line` fields point into the file for messages.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vdrive/od/dictionary.hpp"

namespace vdrive::esi {

struct EsiSyncManager {
  std::string kind;                    // element text: MBoxOut, MBoxIn, Outputs, Inputs
  std::uint16_t start = 0;             // StartAddress
  std::uint16_t default_size = 0;      // DefaultSize (0 when absent)
  std::uint16_t min_size = 0, max_size = 0;  // MinSize / MaxSize (0 when absent)
  std::uint8_t control = 0;            // ControlByte
  bool enable = false;                 // Enable
  int line = 0;
};

struct EsiPdoEntry {
  std::uint16_t index = 0;             // 0: padding
  std::uint8_t subindex = 0;
  std::uint16_t bit_length = 0;
  std::string name;
  std::string data_type;               // as written ("UINT", "BOOL", ...), "" for padding
  int line = 0;
};

struct EsiPdo {
  std::uint16_t index = 0;
  std::string name;
  bool fixed = false;
  bool mandatory = false;
  std::optional<std::uint8_t> sm;      // the SyncManager it is assigned to by default
  std::vector<std::uint16_t> exclude;  // PDOs that cannot be assigned together with this one
  std::vector<EsiPdoEntry> entries;
  int line = 0;
};

struct EsiOpMode {
  std::string name, description;
  std::uint16_t assign_activate = 0;   // the value for 0x0980 (0x0300: SYNC0, 0x0700: SYNC0+1)
  std::int32_t cycle_time_sync0_factor = 0;  // CycleTimeSync0@Factor (0 when absent)
  std::int32_t shift_time_sync0 = 0;   // ShiftTimeSync0 (ns)
  std::int32_t cycle_time_sync1_factor = 0;
  std::int32_t shift_time_sync1 = 0;
};

struct EsiDevice {
  std::string file;                    // for messages
  int line = 0;                        // of <Device>
  std::uint32_t vendor_id = 0;
  std::string vendor_name;
  std::uint32_t product_code = 0, revision = 0;
  std::string type_text;               // <Type> text: the order code
  std::string name;                    // <Name>, English (LcId 1033) when there is one
  std::string group_type, group_name;  // <GroupType> and its group's <Name>
  std::string physics;                 // Device@Physics, one letter per port ("YY", "KK", "YYKK"...)
  std::uint32_t profile_no = 0, add_info = 0;  // <Profile><ProfileNo>, <AddInfo>
  bool has_dictionary = false;
  std::vector<od::ObjectDesc> objects; // <Profile><Dictionary><Objects>, value_bytes set
  std::vector<std::string> fmmus;      // <Fmmu> texts in order: Outputs, Inputs, MBoxState
  std::vector<EsiSyncManager> sync_managers;
  std::vector<EsiPdo> rx_pdos, tx_pdos;
  // <Mailbox>: protocols and the CoE flags.
  bool coe = false, foe = false, eoe = false, soe = false, aoe = false, voe = false;
  bool sdo_info = false, pdo_assign = false, pdo_config = false, pdo_upload = false, complete_access = false;
  bool has_dc = false;
  std::vector<EsiOpMode> op_modes;
  // <Eeprom>
  std::optional<std::uint32_t> eeprom_bytes;       // ByteSize
  std::vector<std::uint8_t> config_data;           // SII words 0.. (at most 8)
  std::vector<std::uint8_t> boot_strap;            // SII words 14h-17h (8 bytes)
  std::vector<std::uint8_t> eeprom_data;           // the whole SII image, when given
  bool explicit_device_id = false;                 // <Info><IdentificationReg134> or IdentificationAdo 0134h
};

}  // namespace vdrive::esi
