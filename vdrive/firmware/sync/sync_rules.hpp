#pragma once
// The synchronisation rules of one product in the form the sync module applies them.
//
// rules_for() takes everything from ProductProfile::sync (profile.yaml `sync:`, docs/profiles.md):
// the SyncSpec itself and the behaviours beside it (1C32h/1C33h-01h rewritten from 0981h at
// PreOp->SafeOp, the 1C33h-01h value for SM2-synchronous inputs, which 1C3xh subindexes count
// misses, whether 20h is set, the objects holding the lost-sync threshold and counting misses).
// No product is named in code.
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
  // The product's rules (profile.yaml `sync:`), including sync_types_follow_dc_activation,
  // input_sm2_sync_type, the counter subindexes, sync_error_flag and the threshold/count objects.
  profile::SyncSpec spec;
  // Consecutive sync edges at the programmed cycle before the drive's cycle counts as locked.
  int lock_edges = 4;
};

SyncRules rules_for(const profile::ProductProfile& product);

// Whether `cycle_ns` is a cycle time the product accepts in SM2/DC mode (list or step rule).
bool cycle_time_accepted(const profile::SyncSpec& spec, std::uint32_t cycle_ns);

}  // namespace vdrive::firmware::sync
