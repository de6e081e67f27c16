#pragma once
// The drive's side of synchronisation at run time: when its cyclic task runs and whether it is
// still in step with the master. Started at PreOp->SafeOp, stopped below SafeOp.
//
//  - Free run: a local timer every `cycle` (the drive's own period when 1C32h-02h is 0).
//  - SM2 event / DC SYNC0: the task runs on each sync edge (SM2 event or SYNC0 AL event). The
//    drive's cycle "locks" (the servo PLL of A6B 5-5 / Err80.3) after `lock_edges` consecutive
//    edges one cycle apart; no lock within `lock_timeout` -> AL 0x002D, back to PreOp.
//    After lock, an edge not seen half a cycle after it was due counts as missed (SM-event missed
//    counter); `missed_threshold` consecutive misses -> AL 0x002C, SafeOp (0 = never). An edge
//    off the locked cycle grid, or a SYNC0 cycle that changed -> AL 0x0032 (PLL error), SafeOp.
//    An SM2 edge sooner than the cycle counts as "cycle time too small".
// DC edges are stamped with the ESC's system time of the pulse (exact); SM2 edges with the time
// the frame arrived, so they are compared with a quarter-cycle tolerance.
// Pure logic on times: the sync module feeds it edges and timer calls. No allocation.
#include <cstdint>
#include <limits>

#include "common/clock.hpp"
#include "vdrive/firmware/sync/sync_check.hpp"

namespace vdrive::firmware::sync {

struct MonitorConfig {
  SyncMode mode = SyncMode::FreeRun;
  Nanos cycle = 0;                 // 0 in SM2 mode with a read-only cycle time: measured at lock
  Nanos lock_timeout = 0;          // 0 = wait for lock forever
  int lock_edges = 4;
  int missed_threshold = 0;        // 0 = lost sync never reported
};

// What one call found; the module acts on it (run the task, count, raise the AL error).
struct MonitorReport {
  bool run_cycle = false;
  int missed = 0;                  // edges found missing by this call
  bool cycle_too_small = false;
  bool locked_now = false;         // the lock was reached by this call
  enum class Fault : std::uint8_t { None, NoLock, LostSync, PllError } fault = Fault::None;
};

class SyncMonitor {
public:
  void start(const MonitorConfig& config, Nanos now);
  void stop();
  bool running() const { return running_; }
  bool locked() const { return locked_; }
  Nanos cycle() const { return config_.cycle; }

  // A sync edge: `edge_time` is the ESC system time of the SYNC0 pulse (DC) or the arrival time
  // of the SM2 event; `now` the firmware's time; `sync0_cycle` the 09A0h value read with it.
  MonitorReport on_edge(std::uint64_t edge_time, Nanos now, std::uint32_t sync0_cycle = 0);
  // The local timer (free-run cycle, missed-edge and lock-timeout supervision).
  MonitorReport on_timer(Nanos now);
  Nanos next_deadline() const;

private:
  MonitorReport fault(MonitorReport r, MonitorReport::Fault f, Nanos now);
  // Whole cycles in `interval` if it is on the cycle grid (DC exactly, SM2 within cycle/4), else 0.
  std::uint64_t cycles_in(std::uint64_t interval) const;

  MonitorConfig config_;
  bool running_ = false;
  bool locked_ = false;
  bool measured_cycle_ = false;    // SM2 with a read-only cycle time: the interval is measured
  Nanos lock_deadline_ = std::numeric_limits<Nanos>::max();
  Nanos next_tick_ = std::numeric_limits<Nanos>::max();    // free run: next local cycle
  Nanos edge_due_ = std::numeric_limits<Nanos>::max();     // locked: latest time the next edge may come
  bool have_edge_ = false;
  std::uint64_t last_edge_ = 0;
  int good_edges_ = 0;
  int consecutive_missed_ = 0;
};

}  // namespace vdrive::firmware::sync
