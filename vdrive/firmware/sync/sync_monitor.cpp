// Run-time synchronisation supervision; see sync_monitor.hpp.
#include "vdrive/firmware/sync/sync_monitor.hpp"

namespace vdrive::firmware::sync {
namespace {
constexpr Nanos kNever = std::numeric_limits<Nanos>::max();
}  // namespace

void SyncMonitor::start(const MonitorConfig& config, Nanos now) {
  config_ = config;
  running_ = true;
  locked_ = false;
  have_edge_ = false;
  good_edges_ = 0;
  consecutive_missed_ = 0;
  edge_due_ = kNever;
  measured_cycle_ = config.mode == SyncMode::Sm2Event && config.cycle == 0;
  next_tick_ = config.mode == SyncMode::FreeRun && config.cycle > 0 ? now + config.cycle : kNever;
  lock_deadline_ =
      config.mode != SyncMode::FreeRun && config.lock_timeout > 0 ? now + config.lock_timeout : kNever;
}

void SyncMonitor::stop() {
  running_ = false;
  locked_ = false;
  next_tick_ = edge_due_ = lock_deadline_ = kNever;
}

std::uint64_t SyncMonitor::cycles_in(std::uint64_t interval) const {
  const auto cycle = static_cast<std::uint64_t>(config_.cycle);
  if (cycle == 0) return 0;
  // DC pulses are exact multiples of 09A0h; SM2 frames arrive with the master's jitter.
  const std::uint64_t tolerance = config_.mode == SyncMode::DcSync0 ? 0 : cycle / 4;
  const std::uint64_t k = (interval + cycle / 2) / cycle;
  const std::uint64_t ideal = k * cycle;
  const std::uint64_t error = interval > ideal ? interval - ideal : ideal - interval;
  return error <= tolerance ? k : 0;
}

MonitorReport SyncMonitor::fault(MonitorReport r, MonitorReport::Fault f, Nanos now) {
  r.fault = f;
  // Synchronisation starts over: the drive tries to lock again (a lost lock is not final: the
  // master may acknowledge and go on, or fall back and reconfigure).
  locked_ = false;
  have_edge_ = false;
  good_edges_ = 0;
  consecutive_missed_ = 0;
  edge_due_ = kNever;
  // NoLock is reported once; its fallback to PreOp stops the monitor.
  lock_deadline_ = f != MonitorReport::Fault::NoLock && config_.lock_timeout > 0
                       ? now + config_.lock_timeout
                       : kNever;
  return r;
}

MonitorReport SyncMonitor::on_edge(std::uint64_t edge_time, Nanos now, std::uint32_t sync0_cycle) {
  MonitorReport r;
  if (!running_ || config_.mode == SyncMode::FreeRun) return r;
  r.run_cycle = true;

  if (config_.mode == SyncMode::DcSync0 && sync0_cycle != 0 &&
      static_cast<Nanos>(sync0_cycle) != config_.cycle) {
    // 09A0h changed after PreOp->SafeOp: the drive's cycle no longer matches SYNC0.
    last_edge_ = edge_time;
    if (locked_) return fault(r, MonitorReport::Fault::PllError, now);
    config_.cycle = sync0_cycle;   // still locking: lock onto the new period (timeout runs on)
    good_edges_ = 0;
    have_edge_ = true;
    return r;
  }

  if (have_edge_) {
    const std::uint64_t interval = edge_time > last_edge_ ? edge_time - last_edge_ : 0;
    const auto cycle = static_cast<std::uint64_t>(config_.cycle);
    const std::uint64_t k = cycles_in(interval);
    if (config_.mode == SyncMode::Sm2Event && cycle > 0 && interval + cycle / 4 < cycle)
      r.cycle_too_small = true;
    last_edge_ = edge_time;
    if (locked_) {
      // Whole cycles later (misses were counted by the timer) is in step; anything else is not.
      if (k == 0 && !r.cycle_too_small) return fault(r, MonitorReport::Fault::PllError, now);
    } else if (k == 1) {
      ++good_edges_;
    } else if (measured_cycle_) {
      config_.cycle = static_cast<Nanos>(interval);   // DS1000A: 1C32h-02h ro, SM2 interval measured
      good_edges_ = 1;
    } else {
      good_edges_ = 0;
    }
  }
  last_edge_ = edge_time;
  have_edge_ = true;

  if (!locked_ && config_.cycle > 0 && good_edges_ + 1 >= config_.lock_edges) {
    locked_ = true;
    r.locked_now = true;
    lock_deadline_ = kNever;
  }
  if (locked_) {
    consecutive_missed_ = 0;
    edge_due_ = now + config_.cycle + config_.cycle / 2;
  }
  return r;
}

MonitorReport SyncMonitor::on_timer(Nanos now) {
  MonitorReport r;
  if (!running_) return r;
  if (now >= next_tick_) {
    r.run_cycle = true;
    next_tick_ += config_.cycle * (1 + (now - next_tick_) / config_.cycle);
  }
  if (!locked_ && now >= lock_deadline_) return fault(r, MonitorReport::Fault::NoLock, now);
  if (locked_ && now >= edge_due_) {
    r.missed = static_cast<int>(1 + (now - edge_due_) / config_.cycle);
    consecutive_missed_ += r.missed;
    edge_due_ += config_.cycle * r.missed;
    if (config_.missed_threshold > 0 && consecutive_missed_ >= config_.missed_threshold)
      return fault(r, MonitorReport::Fault::LostSync, now);
  }
  return r;
}

Nanos SyncMonitor::next_deadline() const {
  if (!running_) return kNever;
  Nanos next = next_tick_;
  if (!locked_ && lock_deadline_ < next) next = lock_deadline_;
  if (locked_ && edge_due_ < next) next = edge_due_;
  return next;
}

}  // namespace vdrive::firmware::sync
