#pragma once
// A product's process data: its default PDO mappings and the rules its mapping objects (16xxh/1Axxh)
// and assignment objects (1C12h/1C13h) follow.
#include <cstdint>
#include <string>
#include <vector>

namespace vdrive::profile {

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

// One mapping object (16xxh/1Axxh) the product has, default mapping or not.
struct PdoObjectRule {
  std::uint16_t index = 0;
  bool fixed = false;                                 // contents cannot be changed (1600h.. writes refused)
  std::uint8_t max_entries = 0;                       // subindexes 01h..max_entries exist
  bool mandatory = false;                             // must stay assigned (ESI RxPdo/TxPdo@Mandatory)
  std::vector<std::uint16_t> excludes;                // never assigned together with these (ESI <Exclude>)
};

// A set of ESM states: the bit is the AL state code for Init (1), PreOp (2), SafeOp (4), Op (8), so
// `set & al_state` tests those four; Boot (AL code 3) is 0x10.
using EsmStateSet = std::uint8_t;
inline constexpr EsmStateSet kStateInit = 0x01, kStatePreOp = 0x02, kStateSafeOp = 0x04, kStateOp = 0x08,
                             kStateBoot = 0x10;

struct PdoRules {
  std::vector<PdoObjectRule> rx_objects;              // 1600h.. in index order
  std::vector<PdoObjectRule> tx_objects;              // 1A00h.. in index order
  std::uint8_t max_rx_assigned = 0;                   // 1C12h-00h maximum
  std::uint8_t max_tx_assigned = 0;                   // 1C13h-00h maximum
  std::uint16_t max_rx_bytes = 0;                     // total RxPDO size limit (bytes, all assigned PDOs)
  std::uint16_t max_tx_bytes = 0;                     // total TxPDO size limit
  bool assign_writable = true;                        // 1C12h/1C13h can be written at all
  bool mapping_writable = true;                       // free mapping (16xxh/1Axxh not all fixed)
  EsmStateSet writable_states = kStatePreOp;          // states in which 1C1xh/16xxh/1Axxh may change
  bool sub0_must_be_zero = true;                      // subindexes >= 1 writable only while sub 0 = 0
  std::uint32_t wrong_state_abort = 0x06010003;       // SDO abort for a write outside writable_states
  bool checked_at_safeop = true;                      // size/mappability checked at PreOp->SafeOp (not on SDO write)
  bool byte_aligned_total = false;                    // total size must be whole bytes (padding rule)
  // SM2/SM3 control byte: the mode bits 1-0 must be 3-buffer (00b) as well as the direction bits 3-2;
  // false: the direction only (A6B Err81.7 names bits 3-2 alone, L33570, L33610).
  bool sm_control_mode_checked = true;
  // A direction with nothing mapped wants its SM2/SM3 disabled: an enabled one is refused even at
  // length 0 (ETG SSC CheckSmSettings; A6B Err81.7 reports SM settings with nothing mapped,
  // L4907, L4915, L4954, L4960, L4974). false: an enabled SM of length 0 passes, as the ESC does not run it.
  // An enabled SM with a length while nothing is mapped is a length fault either way.
  bool unused_sm_must_be_disabled = false;
};

}  // namespace vdrive::profile
