#pragma once
// The PDO rules of one product in the form the PDO module checks them: how many mapping objects
// and entries exist, how many PDOs may be assigned, how many bytes each direction may carry,
// when mapping/assignment objects may be written and which SDO abort a refused write gets, and
// which checks happen at SDO-write time rather than at PreOp->SafeOp.
//
// limits_for() takes them from ProductProfile::pdo_rules (profile.yaml `pdo_rules`), and
// watchdog_limits_for() from ProductProfile::sync.watchdog; no product is named in code.
#include <cstdint>

#include "ethercat/al_state.hpp"
#include "vdrive/od/sdo_abort.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::pdo {

// Rx = outputs (master -> slave, 16xxh, 1C12h, SM2); Tx = inputs (slave -> master, 1Axxh, 1C13h, SM3).
enum class Direction : std::uint8_t { Rx, Tx };

inline constexpr std::uint16_t kRxMappingFirst = 0x1600;
inline constexpr std::uint16_t kTxMappingFirst = 0x1A00;
inline constexpr std::uint16_t kRxAssign = 0x1C12;
inline constexpr std::uint16_t kTxAssign = 0x1C13;
inline constexpr std::uint16_t kSm2Sync = 0x1C32;  // 1C32h: SM2 (outputs) synchronisation
inline constexpr int kOutputsSm = 2;
inline constexpr int kInputsSm = 3;

// Upper bounds of the fixed-size tables (no product exceeds them: A6B 4 x 32 entries).
inline constexpr int kMaxAssigned = 8;
inline constexpr int kMaxEntriesPerPdo = 64;
inline constexpr int kMaxMappedEntries = 256;   // per direction, all assigned PDOs together
inline constexpr int kMaxPdoBytes = 1024;       // per direction

struct DirectionLimits {
  // The mapping objects lie in first_index..last_index (none when last_index < first_index). The
  // range may have gaps (an ESI device's 1A00h and 1A02h): where it matters, the dictionary says
  // which objects exist.
  std::uint16_t first_index = 0;      // 1600h / 1A00h
  std::uint16_t last_index = 0;       // the highest mapping object
  std::uint8_t max_entries = 0;       // subindexes 01h..max of one mapping object
  std::uint8_t max_assigned = 0;      // 1C12h/1C13h subindex 00h maximum
  std::uint16_t max_bytes = 0;        // all assigned PDOs of the direction together

  bool is_mapping_object(std::uint16_t index) const { return index >= first_index && index <= last_index; }
};

struct PdoLimits {
  DirectionLimits rx, tx;
  // Bit per ecat::AlState value (1 << state) in which 1C12h/1C13h/16xxh/1Axxh may be written.
  std::uint32_t writable_states = 1u << static_cast<unsigned>(ecat::AlState::PreOp);
  od::SdoAbort wrong_state_abort = od::SdoAbort::SubindexCannotBeWritten;
  bool sub0_must_be_zero = true;      // subindexes 01h+ only while 00h = 0 (ETG.1020)
  bool mappable_checked_on_write = true;  // 06040041h at the SDO write (else at PreOp->SafeOp)
  bool length_checked_on_write = true;    // 06040042h at the SDO write (else at PreOp->SafeOp)

  const DirectionLimits& of(Direction d) const { return d == Direction::Rx ? rx : tx; }
  bool writable_in(ecat::AlState s) const {
    return (writable_states & (1u << static_cast<unsigned>(s))) != 0;
  }
};

PdoLimits limits_for(const profile::ProductProfile& product);

// The product's process-data watchdog setting rule (A6B Err81.4, DS5C1 E-814): with the SM2
// watchdog enabled, its time must be at least min_cycles x cycle time (SM2/DC) or
// min_free_run_ns (free run). 0 = no check.
struct WatchdogLimits {
  std::uint8_t min_cycles = 0;
  std::uint32_t min_free_run_ns = 0;
};

WatchdogLimits watchdog_limits_for(const profile::ProductProfile& product);

}  // namespace vdrive::firmware::pdo
