#pragma once
// The PreOp->SafeOp synchronisation check (A6B Err81.0/81.5/81.6, DS5C1 E-810/815/816): from what
// the master configured in the ESC (0981h DC activation, 09A0h SYNC0 cycle) and in 1C32h/1C33h,
// decide the sync mode and cycle the drive will run, or the AL status code that refuses SafeOp.
// Pure functions over values; the sync module reads the registers and objects. No allocation.
#include <cstdint>

#include "ethercat/registers.hpp"
#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/sync/sync_rules.hpp"

namespace vdrive::firmware::sync {

enum class SyncMode : std::uint8_t { FreeRun, Sm2Event, DcSync0 };

// What the master configured, as read at PreOp->SafeOp.
struct SyncSettings {
  std::uint8_t dc_activation = 0;      // 0981h
  std::uint32_t sync0_cycle_ns = 0;    // 09A0h
  std::uint16_t output_sync_type = 0;  // 1C32h-01h
  std::uint16_t input_sync_type = 0;   // 1C33h-01h
  std::uint32_t cycle_time_ns = 0;     // 1C32h-02h
};

// 0981h bits 2-0: cyclic operation, SYNC0, SYNC1 (the other bits are activation options).
inline constexpr std::uint8_t kDcActivationMask = ecat::reg::dc_activation::kCyclicOperation |
                                                  ecat::reg::dc_activation::kSync0 |
                                                  ecat::reg::dc_activation::kSync1;
inline constexpr std::uint8_t kDcCyclicSync0 =
    ecat::reg::dc_activation::kCyclicOperation | ecat::reg::dc_activation::kSync0;

struct SyncDecision {
  CheckResult result;                  // pass, or the code and fallback state
  SyncMode mode = SyncMode::FreeRun;
  std::uint32_t cycle_ns = 0;          // the cycle the drive runs (0 in free run: 1C32h-02h may be 0)
};

// With spec.sync_types_follow_dc_activation (e.g. A6B) 1C32h-01h/1C33h-01h follow 0981h (DC on:
// DC SYNC0; DC off: DC SYNC0 becomes free run). Returns the settings, rewritten when the product does this.
SyncSettings rewrite_from_dc_activation(const SyncRules& rules, SyncSettings settings);

// Order of the checks: sync types (0x0028), DC activation (0x0030), cycle time (0x0035).
// The fallback state is PreOp for all three (the drive stays where it was).
SyncDecision check_sync_settings(const SyncRules& rules, const profile::AlStatusCodes& codes,
                                 const SyncSettings& settings);

}  // namespace vdrive::firmware::sync
