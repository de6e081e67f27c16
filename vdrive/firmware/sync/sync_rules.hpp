#pragma once
// The synchronisation rules of one product in the form the sync module applies them.
//
// rules_for() takes ProductProfile::sync (SyncSpec) when the profile carries it (a cycle list or
// step is set); otherwise it falls back to the values in sync_rules.cpp, each read from the
// product's manual (one place for all constants). A few behaviours SyncSpec does not describe are
// added here per product: the A6B rewrites 1C32h/1C33h-01h from 0981h at PreOp->SafeOp, the
// counters' subindexes differ (the A6B and DS5C1 swap 0Bh/0Ch against ETG.1020), the A6B takes
// its lost-sync threshold from object 3742h and counts sync errors in 4F78h.
#include <cstdint>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::sync {

inline constexpr std::uint16_t kOutputSync = 0x1C32;  // SM2 (outputs) synchronisation
inline constexpr std::uint16_t kInputSync = 0x1C33;   // SM3 (inputs) synchronisation

// 1C3xh subindexes (ETG.1020).
namespace sub {
inline constexpr std::uint8_t kSyncType = 0x01;
inline constexpr std::uint8_t kCycleTime = 0x02;
inline constexpr std::uint8_t kShiftTime = 0x03;
inline constexpr std::uint8_t kSupportedTypes = 0x04;
inline constexpr std::uint8_t kMinCycleTime = 0x05;
inline constexpr std::uint8_t kCalcAndCopyTime = 0x06;
inline constexpr std::uint8_t kDelayTime = 0x09;
inline constexpr std::uint8_t kSync0CycleTime = 0x0A;
inline constexpr std::uint8_t kSyncError = 0x20;
}  // namespace sub

struct SyncRules {
  profile::SyncSpec spec;
  // A6B (L7750-L7780, L8000-L8030): at PreOp->SafeOp 1C32h-01h/1C33h-01h follow 0981h:
  // DC on -> DC SYNC0; DC off -> a DC SYNC0 setting becomes free run.
  bool mode_follows_dc_activation = false;
  // The 1C33h-01h value meaning "inputs synchronous with the SM2 event": 22h (ETG.1020, A6B);
  // the DS5C1 uses 01h for both objects (L5669, E-816 L7128).
  std::uint16_t input_sm2_sync_type = 0x22;
  // Subindexes of the two counters (0 = not counted: the manual says "not supported").
  std::uint8_t sm_event_missed_sub = 0;
  std::uint8_t cycle_too_small_sub = 0;
  bool sync_error_flag = false;           // 20h is set on lost sync
  // Object whose bits 3-0 hold the consecutive-miss threshold (A6B 3742h), 0 = use
  // spec.missed_sync_threshold.
  std::uint16_t missed_threshold_object = 0;
  // Object counting SYNC/IRQ misses (A6B 4F78h "Synchronization signal error count"), 0 = none.
  std::uint16_t sync_error_count_object = 0;
  // Consecutive sync edges at the programmed cycle before the drive's cycle counts as locked.
  int lock_edges = 4;
};

SyncRules rules_for(const profile::ProductProfile& product);

// Whether `cycle_ns` is a cycle time the product accepts in SM2/DC mode (list or step rule).
bool cycle_time_accepted(const profile::SyncSpec& spec, std::uint32_t cycle_ns);

}  // namespace vdrive::firmware::sync
