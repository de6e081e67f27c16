// Sync rules per product: ProductProfile::sync when loaded, else the manuals' values below.
#include "vdrive/firmware/sync/sync_rules.hpp"

namespace vdrive::firmware::sync {
namespace {

using profile::SyncSpec;

// Panasonic MINAS-A6B, SX-DSV03241 5-5 (L7687-L8783), 8-2 Err80.x/81.x (L32952-L33624).
SyncSpec a6b_manual() {
  SyncSpec s;
  s.free_run = s.sm2_event = s.dc_sync0 = true;                  // L3857-L4236
  s.cycle_times_ns = {125000, 250000, 500000, 1000000, 2000000, 4000000, 8000000, 10000000};  // Err81.0
  s.cycle_min_ns = 125000;
  s.cycle_max_ns = 10000000;
  s.free_run_min_interval_ns = 250000;                           // L4133-L4155
  s.cycle_must_equal_sync0 = true;                               // Err81.0: 09A0h = 1C32h-02h
  s.accepted_dc_activation = {0x00, 0x03};                       // Err81.5 L33482-L33506
  s.mode_min_cycle = {{1, 250000}, {3, 250000}, {4, 250000}};    // pp/pv/tq L14414, L20771, L23430
  s.sm2.default_sync_type = 0x00;                                // factory value not in the manual
  s.sm2.accepted_sync_types = {0x00, 0x01, 0x02};                // Err81.6
  // Factory value not in the manual: 0 (the master writes it, as the 1-1 example does, L1545-L1551).
  s.sm2.default_cycle_time_ns = 0;
  s.sm2.cycle_time_writable = true;
  s.sm2.shift_time_writable = false;                             // 03h ro, not supported
  s.sm2.supported_sync_types = 0x0007;                           // L7800-L7830
  s.sm2.min_cycle_time_ns = 125000;
  s.sm2.calc_and_copy_time_ns = 25000;
  s.sm2.delay_time_ns = 0;
  s.sm3 = s.sm2;
  s.sm3.accepted_sync_types = {0x00, 0x02, 0x22};
  s.sm3.cycle_time_writable = false;                             // 02h ro = 1C32h-02h
  s.sm3.shift_time_writable = true;                              // L8044-L8050
  s.sm3.supported_sync_types = 0x0027;                           // input shift supported
  s.sm3.calc_and_copy_time_ns = 45000;                           // L8119-L8123
  s.input_shift = {125000, 3875000, true, {}};
  s.watchdog = {2, 2000000};                                     // Err81.4
  s.pll_lock_timeout_ns = 1000000000;                            // Err80.3
  s.missed_sync_threshold = 0;                                   // from 3742h, see rules_for
  return s;
}

// Xinje DS5C1 (firmware 3791 and later), 6.2.8 (L2663-L2691), 8.2.5 (L5658-L5725), E-8xx (L7109-L7139).
SyncSpec ds5c1_manual() {
  SyncSpec s;
  s.free_run = s.sm2_event = s.dc_sync0 = true;
  s.cycle_times_ns = {1000000, 2000000, 4000000, 8000000, 10000000};  // E-810
  s.cycle_min_ns = 1000000;
  s.cycle_max_ns = 10000000;
  s.cycle_must_equal_sync0 = true;
  s.accepted_dc_activation = {0x00, 0x03};                       // E-815
  s.sm2.default_sync_type = 0x00;                                // not in the manual
  s.sm2.accepted_sync_types = {0x00, 0x01, 0x02};                // E-816
  s.sm2.default_cycle_time_ns = 0;                               // not in the manual
  s.sm2.cycle_time_writable = true;
  s.sm2.shift_time_writable = true;                              // 03h rw
  s.sm2.supported_sync_types = 0x0007;                           // L5672-L5676
  s.sm2.min_cycle_time_ns = 1000000;                             // value not given: the shortest cycle
  s.sm3 = s.sm2;                                                 // same table, 1C33h-01h 00/01/02h
  s.watchdog = {2, 0};                                           // E-814
  s.pll_lock_timeout_ns = 1000000000;                            // E-803
  s.missed_sync_threshold = 0;                                   // E-807 names no value: off
  return s;
}

// DS1000A-EC, 5.x sync modes (L3405-L3429, L691-L712), 1C32h/1C33h (L4699-L4790).
SyncSpec ds1000a_manual() {
  SyncSpec s;
  s.free_run = true;                                             // 1C32h-01h defaults to 0 (L4703)
  s.sm2_event = s.dc_sync0 = true;
  s.cycle_step_ns = 1000000;                                     // >= 1 ms in 1 ms steps (L691-L693)
  s.cycle_min_ns = 1000000;
  s.cycle_max_ns = 4294000000u;                                  // no upper limit; <= 10 ms recommended
  s.cycle_must_equal_sync0 = false;                              // 02h ro: the drive copies 09A0h
  s.accepted_dc_activation = {0x00, 0x03};                       // SYNC0 only: not in manual
  s.sm2.default_sync_type = 0x00;
  s.sm2.accepted_sync_types = {0x00, 0x01, 0x02};
  s.sm2.default_cycle_time_ns = 0;
  s.sm2.cycle_time_writable = false;
  s.sm2.supported_sync_types = 0x0000;                           // sic (L4730)
  s.sm2.min_cycle_time_ns = 1000000;
  s.sm2.calc_and_copy_time_ns = 125000;
  s.sm2.error_counters = true;                                   // 0Bh-0Dh, 20h (L4742-L4753)
  s.sm3 = s.sm2;
  s.sm3.accepted_sync_types = {0x00, 0x02, 0x22};                // ETG.1020 1C33h values
  s.pll_lock_timeout_ns = 0;                                     // not in manual: no timeout
  s.missed_sync_threshold = 0;                                   // not in manual: off
  return s;
}

// Any other product: ETG.1020 modes, any cycle from 125 us.
SyncSpec generic() {
  SyncSpec s;
  s.free_run = s.sm2_event = s.dc_sync0 = true;
  s.cycle_step_ns = 1;
  s.cycle_min_ns = 125000;
  s.cycle_max_ns = 0xFFFFFFFFu;
  s.accepted_dc_activation = {0x00, 0x03};
  s.sm2.accepted_sync_types = {0x00, 0x01, 0x02};
  s.sm2.supported_sync_types = 0x0007;
  s.sm3 = s.sm2;
  s.sm3.accepted_sync_types = {0x00, 0x02, 0x22};
  s.pll_lock_timeout_ns = 1000000000;
  s.missed_sync_threshold = 3;
  return s;
}

}  // namespace

SyncRules rules_for(const profile::ProductProfile& product) {
  SyncRules r;
  const bool loaded = !product.sync.cycle_times_ns.empty() || product.sync.cycle_step_ns != 0;
  if (product.id == "a6b") {
    r.spec = loaded ? product.sync : a6b_manual();
    r.mode_follows_dc_activation = true;
    r.missed_threshold_object = 0x3742;   // bits 3-0: Err80.7 threshold, 0 = off (L33248-L33264)
    r.sync_error_count_object = 0x4F78;   // L32136-L32142
  } else if (product.id == "ds5c1") {
    r.spec = loaded ? product.sync : ds5c1_manual();
    r.input_sm2_sync_type = 0x01;
    r.sync_error_flag = true;             // 20h "Sync error" (0Bh-0Eh "not supported")
  } else if (product.id == "ds1000a") {
    r.spec = loaded ? product.sync : ds1000a_manual();
    r.sm_event_missed_sub = 0x0B;         // ETG.1020 order (L4742-L4748)
    r.cycle_too_small_sub = 0x0C;
    r.sync_error_flag = true;
  } else {
    r.spec = loaded ? product.sync : generic();
    r.sm_event_missed_sub = 0x0B;
    r.cycle_too_small_sub = 0x0C;
    r.sync_error_flag = true;
  }
  return r;
}

bool cycle_time_accepted(const profile::SyncSpec& spec, std::uint32_t cycle_ns) {
  return spec.accepts_cycle(cycle_ns);
}

}  // namespace vdrive::firmware::sync
