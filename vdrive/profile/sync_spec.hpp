#pragma once
// A product's synchronisation (1C32h/1C33h, ETG.1020 / ETG.6010): sync modes, cycle times, shift
// times, the process-data watchdog rule and how it counts and reports lost sync.
#include <cstdint>
#include <vector>

namespace vdrive::profile {

// Sync types as 1C32h-01h/1C33h-01h hold them (ETG.1020): the product's accepted values are listed
// per object in SyncObjectSpec::accepted_sync_types.
enum class SyncType : std::uint16_t {
  FreeRun = 0x00,         // local timer, no synchronisation
  Sm2Event = 0x01,        // 1C32h: synchronous with SM2 event
  DcSync0 = 0x02,         // synchronous with SYNC0
  DcSync1 = 0x03,         // synchronous with SYNC1
  Sm2EventInputs = 0x22,  // 1C33h: inputs latched synchronous with the SM2 event
};

// The values one of 1C32h (outputs, SM2) or 1C33h (inputs, SM3) holds after power-up and what the
// product accepts there. Times in ns. Where the manual says "not supported" the value is 0 (the
// subindex reads 0); which subindexes exist is the object dictionary's business (objects.yaml).
struct SyncObjectSpec {
  std::uint16_t default_sync_type = 0;                // 01h after power-up
  std::vector<std::uint16_t> accepted_sync_types;     // 01h values a write / PS check accepts
  std::uint32_t default_cycle_time_ns = 0;            // 02h after power-up
  bool cycle_time_writable = true;                    // 02h rw (else ro, copied from 1C32h/09A0h)
  std::uint32_t default_shift_time_ns = 0;            // 03h after power-up
  bool shift_time_writable = false;                   // 03h rw
  std::uint16_t supported_sync_types = 0;             // 04h (bit0 free run, bit1 SM, bits4-2 DC, bits6-5 shift)
  std::uint32_t min_cycle_time_ns = 0;                // 05h
  std::uint32_t calc_and_copy_time_ns = 0;            // 06h
  std::uint32_t delay_time_ns = 0;                    // 09h
  bool error_counters = false;                        // 0Bh-0Eh are real counters (else read 0); SyncSpec says which counts what
};

// Shift-time rule for 1C33h-03h (input latch after SYNC0/SM2) or 1C32h-03h. max_ns = 0: only 0 is
// accepted (the product has no shift).
struct ShiftTimeRule {
  std::uint32_t step_ns = 0;                          // value must be a multiple of this (0 = any)
  std::uint32_t max_ns = 0;                           // largest accepted value
  bool below_cycle_time = true;                       // must be < 1C32h-02h
  std::vector<std::uint32_t> cycle_times_ns;          // cycles at which a shift is accepted (empty = all)
};

// Process-data (SM2) watchdog rule checked at PreOp->SafeOp when the watchdog is enabled
// (SM2 control bit 6): the timeout, (0400h + 2) * 40 ns * 0420h, must be at least
// min_cycles * cycle time in SM2/DC mode, and at least min_free_run_ns in free run.
struct WatchdogRule {
  std::uint8_t min_cycles = 0;                        // e.g. A6B Err81.4: 2 x cycle (0 = no check)
  std::uint32_t min_free_run_ns = 0;                  // e.g. A6B Err81.4: 2 ms in free run
};

// A drive mode that needs a longer cycle than the product's minimum (e.g. A6B pp/pv/tq >= 250 us).
struct ModeCycleLimit {
  std::int8_t mode = 0;                               // 6060h value
  std::uint32_t min_cycle_ns = 0;
};

struct SyncSpec {
  bool free_run = false;                              // sync modes the product runs in
  bool sm2_event = false;
  bool dc_sync0 = false;
  bool dc_sync1 = false;
  // Cycle times accepted in SM2/DC (1C32h-02h, 09A0h), ascending. When `cycle_step_ns` != 0 the
  // list is empty and any multiple of the step in [cycle_min_ns, cycle_max_ns] is accepted.
  std::vector<std::uint32_t> cycle_times_ns;
  std::uint32_t cycle_step_ns = 0;
  std::uint32_t cycle_min_ns = 0, cycle_max_ns = 0;   // always set: the accepted range
  std::uint32_t free_run_min_interval_ns = 0;         // fastest PDO rate the product takes in free run (0 = not stated)
  bool cycle_must_equal_sync0 = true;                 // DC: 09A0h must equal 1C32h-02h
  std::vector<std::uint8_t> accepted_dc_activation;   // 0981h values accepted at PS (e.g. 0x00, 0x03)
  std::vector<ModeCycleLimit> mode_min_cycle;         // per-mode cycle minimums
  SyncObjectSpec sm2;                                 // 1C32h
  SyncObjectSpec sm3;                                 // 1C33h
  ShiftTimeRule input_shift;                          // 1C33h-03h
  ShiftTimeRule output_shift;                         // 1C32h-03h
  WatchdogRule watchdog;
  std::uint32_t pll_lock_timeout_ns = 0;              // sync must lock within this after PS (0 = not stated)
  std::uint8_t missed_sync_threshold = 0;             // consecutive SYNC0/IRQ misses before a sync error (0 = never)
  // Where the product keeps that threshold instead: bits 3-0 of this object's subindex 0 (A6B 3742h);
  // 0 = missed_sync_threshold applies.
  std::uint16_t missed_sync_threshold_object = 0;
  // Object (subindex 0) counting SYNC0/IRQ misses (A6B 4F78h); 0 = none.
  std::uint16_t sync_error_count_object = 0;
  // At PreOp->SafeOp 1C32h-01h/1C33h-01h are rewritten from 0981h: DC on -> DC SYNC0; DC off -> a
  // DC SYNC0 setting becomes free run (A6B L7750-L7780).
  bool sync_types_follow_dc_activation = false;
  // The 1C33h-01h value for "inputs synchronous with the SM2 event": 22h (ETG.1020), 01h on the DS5C1.
  std::uint16_t input_sm2_sync_type = 0x22;
  // 1C32h/1C33h subindexes counting missed SM2/SYNC0 events and too-short cycles (0 = not counted).
  std::uint8_t sm_event_missed_subindex = 0;
  std::uint8_t cycle_too_small_subindex = 0;
  bool sync_error_flag = false;                       // 1C32h/1C33h-20h is set on lost sync
  // SM-synchronous mode: an SM2 event out of step with the cycle is a PLL error (the built-in
  // drives lock onto the SM2 cycle); false: SM2 events are taken as they come (ETG SSC devices).
  bool sm2_in_step_check = true;

  // True when `ns` is a cycle time the product accepts in SM2/DC mode (1C32h-02h / 09A0h).
  bool accepts_cycle(std::uint32_t ns) const {
    if (cycle_step_ns != 0) return ns >= cycle_min_ns && ns <= cycle_max_ns && ns % cycle_step_ns == 0;
    for (const std::uint32_t c : cycle_times_ns)
      if (c == ns) return true;
    return false;
  }
  // The shortest cycle `mode` (6060h) runs at: its mode_min_cycle entry, else cycle_min_ns.
  std::uint32_t min_cycle_for_mode(std::int8_t mode) const {
    for (const ModeCycleLimit& l : mode_min_cycle)
      if (l.mode == mode) return l.min_cycle_ns;
    return cycle_min_ns;
  }
};

}  // namespace vdrive::profile
