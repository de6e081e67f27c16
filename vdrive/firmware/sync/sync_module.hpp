#pragma once
// Synchronisation of the drive to the master, as a firmware module:
//  - PreOp->SafeOp: reads 0981h/09A0h through the PDI and 1C32h/1C33h, applies the product's
//    rewrite (profile sync.sync_types_follow_dc_activation) and checks (sync_check.hpp): 0x0028 / 0x0030 / 0x0035, fallback PreOp.
//    Publishes what the drive runs: 1C3xh-0Ah = 09A0h in DC mode, read-only cycle times.
//  - SafeOp/Op: runs the cyclic task on SYNC0 (AL event bit 2, acknowledged by reading 098Eh;
//    the pulse is stamped with its system time from 0990h - 09A0h), on the SM2 event (bit 10) or
//    on a local timer (free run), and supervises the lock (SyncMonitor): 0x002D (no lock in
//    time, PreOp), 0x002C (missed SYNC0/IRQ >= threshold, SafeOp), 0x0032 (cycle changed, SafeOp).
//    Counts misses in the 1C3xh subindexes and the object the profile names (sync.*_subindex,
//    sync.sync_error_count_object), sets 1C3xh-20h on lost sync where sync.sync_error_flag says so.
// The cyclic work itself (process data, drive control) is registered with on_cycle().
// In SM2 mode the registered task must read the SM2 buffer, which acknowledges the event.
// Nothing allocates after construction.
#include <cstdint>
#include <functional>
#include <vector>

#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/sync/sync_check.hpp"
#include "vdrive/firmware/sync/sync_monitor.hpp"
#include "vdrive/firmware/sync/sync_objects.hpp"
#include "vdrive/firmware/sync/sync_rules.hpp"

namespace vdrive::firmware::sync {

class SyncModule final : public FirmwareModule {
public:
  explicit SyncModule(const FirmwareContext& context);

  // Work to run once per drive cycle in SafeOp and Op, in registration order. Register at
  // construction time only (this allocates); the cycle itself allocates nothing.
  void on_cycle(std::function<void(Nanos)> task);
  // Told the sync mode each time the cycle starts (PreOp->SafeOp), e.g. so the process-data
  // module exchanges at SYNC0 in DC mode and on its SM2 event otherwise. Construction time only.
  void on_start(std::function<void(SyncMode)> listener);

  // Control power on: the 1C32h/1C33h values the drive computes at boot, nothing running.
  void power_on(Nanos now) override;
  std::uint32_t serviced_events() const override;
  void on_events(std::uint32_t events, Nanos now) override;
  CheckResult check_transition(ecat::AlState from, ecat::AlState to) override;
  void entered(ecat::AlState from, ecat::AlState to, Nanos now) override;
  void tick(Nanos now) override;
  Nanos next_deadline() const override;

  // What the drive runs (tests, status).
  SyncMode mode() const { return decision_.mode; }
  bool running() const { return monitor_.running(); }
  bool locked() const { return monitor_.locked(); }
  std::uint64_t cycles() const { return cycles_; }
  const SyncRules& rules() const { return rules_; }

private:
  // `cycle_at`: when the cycle's sync point was (the SYNC0 pulse), which the loop may see late.
  void handle(const MonitorReport& report, Nanos cycle_at);
  void run_cycle(Nanos now);
  void publish_running_values(const SyncSettings& settings);
  MonitorConfig monitor_config() const;

  FirmwareContext context_;
  SyncRules rules_;
  SyncObjects objects_;
  SyncMonitor monitor_;
  SyncDecision decision_;
  std::vector<std::function<void(Nanos)>> tasks_;
  std::vector<std::function<void(SyncMode)>> start_listeners_;
  std::uint64_t cycles_ = 0;
};

}  // namespace vdrive::firmware::sync
