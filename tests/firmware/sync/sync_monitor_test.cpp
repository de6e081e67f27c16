// The drive's run-time synchronisation: lock after consecutive edges, lock timeout, missed edges
// and lost sync, cycle changes (PLL error), free-run timer, measured SM2 cycle.
#include <gtest/gtest.h>

#include "vdrive/firmware/sync/sync_monitor.hpp"

namespace vdrive::firmware::sync {
namespace {

using Fault = MonitorReport::Fault;
constexpr Nanos kMs = 1000000;

MonitorConfig dc_config(Nanos cycle, int threshold = 3) {
  MonitorConfig c;
  c.mode = SyncMode::DcSync0;
  c.cycle = cycle;
  c.lock_timeout = 1000 * kMs;
  c.lock_edges = 4;
  c.missed_threshold = threshold;
  return c;
}

// Feeds DC edges at system times base + k*cycle, seen `latency` ns later in firmware time.
struct DcDriver {
  SyncMonitor& m;
  std::uint64_t system_base;
  Nanos firmware_base;
  Nanos cycle;
  MonitorReport edge(int k, Nanos latency = 0) {
    return m.on_edge(system_base + static_cast<std::uint64_t>(k * cycle), firmware_base + k * cycle + latency,
                     static_cast<std::uint32_t>(cycle));
  }
};

TEST(SyncMonitor, LocksAfterConsecutiveEdgesAndRunsEveryEdge) {
  SyncMonitor m;
  m.start(dc_config(kMs), 0);
  DcDriver d{m, 5'000'000'000ull, 100 * kMs, kMs};
  int runs = 0;
  for (int k = 0; k < 3; ++k) {
    const MonitorReport r = d.edge(k, 700);   // firmware sees the pulse with some latency
    runs += r.run_cycle;
    EXPECT_FALSE(r.locked_now);
    EXPECT_FALSE(m.locked());
  }
  const MonitorReport r = d.edge(3, 300);
  EXPECT_TRUE(r.locked_now);
  EXPECT_TRUE(m.locked());
  EXPECT_EQ(runs + r.run_cycle, 4);
  EXPECT_EQ(r.fault, Fault::None);
}

TEST(SyncMonitor, NoEdgesMeansNoLockAfterTheTimeout) {
  SyncMonitor m;
  m.start(dc_config(kMs), 10 * kMs);
  EXPECT_EQ(m.next_deadline(), 1010 * kMs);
  EXPECT_EQ(m.on_timer(1009 * kMs).fault, Fault::None);
  EXPECT_EQ(m.on_timer(1010 * kMs).fault, Fault::NoLock);
}

TEST(SyncMonitor, MissedEdgesAreCountedAndTheThresholdLosesSync) {
  SyncMonitor m;
  m.start(dc_config(kMs, 3), 0);
  DcDriver d{m, 1'000'000ull, 10 * kMs, kMs};
  for (int k = 0; k < 4; ++k) d.edge(k);
  ASSERT_TRUE(m.locked());
  // Edge 4 is due at 14 ms; missed once half a cycle later.
  EXPECT_EQ(m.next_deadline(), 13 * kMs + kMs + kMs / 2);
  MonitorReport r = m.on_timer(m.next_deadline());
  EXPECT_EQ(r.missed, 1);
  EXPECT_EQ(r.fault, Fault::None);
  // Edge 5 arrives on the grid: in step again, consecutive count restarts.
  r = d.edge(5);
  EXPECT_EQ(r.fault, Fault::None);
  EXPECT_TRUE(r.run_cycle);
  // Then three in a row are missed: lost sync.
  EXPECT_EQ(m.on_timer(m.next_deadline()).missed, 1);
  EXPECT_EQ(m.on_timer(m.next_deadline()).missed, 1);
  r = m.on_timer(m.next_deadline());
  EXPECT_EQ(r.missed, 1);
  EXPECT_EQ(r.fault, Fault::LostSync);
  EXPECT_FALSE(m.locked());
}

TEST(SyncMonitor, ThresholdZeroNeverLosesSync) {
  SyncMonitor m;
  m.start(dc_config(kMs, 0), 0);
  DcDriver d{m, 0, 0, kMs};
  for (int k = 0; k < 4; ++k) d.edge(k);
  int missed = 0;
  for (int i = 0; i < 50; ++i) {
    const MonitorReport r = m.on_timer(m.next_deadline());
    missed += r.missed;
    ASSERT_EQ(r.fault, Fault::None);
  }
  EXPECT_EQ(missed, 50);
}

TEST(SyncMonitor, ChangedSync0CycleAfterLockIsAPllError) {
  SyncMonitor m;
  m.start(dc_config(kMs), 0);
  DcDriver d{m, 0, 0, kMs};
  for (int k = 0; k < 4; ++k) d.edge(k);
  ASSERT_TRUE(m.locked());
  const MonitorReport r = m.on_edge(4 * kMs, 4 * kMs, 2 * kMs);   // master rewrote 09A0h
  EXPECT_EQ(r.fault, Fault::PllError);
}

TEST(SyncMonitor, PhaseJumpAfterLockIsAPllError) {
  SyncMonitor m;
  m.start(dc_config(kMs), 0);
  DcDriver d{m, 0, 0, kMs};
  for (int k = 0; k < 4; ++k) d.edge(k);
  // A new start time: pulses 0.3 cycles off the old grid.
  const MonitorReport r = m.on_edge(4 * kMs + 300000, 4 * kMs + 300000, kMs);
  EXPECT_EQ(r.fault, Fault::PllError);
  // Two cycles later on the grid (one missed in between) would have been fine.
  SyncMonitor m2;
  m2.start(dc_config(kMs), 0);
  DcDriver d2{m2, 0, 0, kMs};
  for (int k = 0; k < 4; ++k) d2.edge(k);
  EXPECT_EQ(d2.edge(6).fault, Fault::None);
}

TEST(SyncMonitor, FreeRunTicksEveryCycleWithoutSupervision) {
  SyncMonitor m;
  MonitorConfig c;
  c.mode = SyncMode::FreeRun;
  c.cycle = 2 * kMs;
  c.lock_timeout = 1000 * kMs;
  m.start(c, 0);
  int runs = 0;
  Nanos t = 0;
  for (int i = 0; i < 100; ++i) {
    t = m.next_deadline();
    const MonitorReport r = m.on_timer(t);
    runs += r.run_cycle;
    EXPECT_EQ(r.fault, Fault::None);
  }
  EXPECT_EQ(runs, 100);
  EXPECT_EQ(t, 200 * kMs);
  EXPECT_FALSE(m.on_edge(0, t).run_cycle);   // edges do not drive a free-running drive
}

TEST(SyncMonitor, Sm2EdgesWithJitterLockAndEarlyFramesCountAsCycleTooSmall) {
  SyncMonitor m;
  MonitorConfig c;
  c.mode = SyncMode::Sm2Event;
  c.cycle = kMs;
  c.lock_timeout = 1000 * kMs;
  c.lock_edges = 4;
  c.missed_threshold = 3;
  m.start(c, 0);
  const Nanos jitter[] = {0, 40000, -30000, 100000, -90000};
  for (int k = 0; k < 5; ++k) {
    const Nanos t = 10 * kMs + k * kMs + jitter[k];
    EXPECT_EQ(m.on_edge(static_cast<std::uint64_t>(t), t).fault, Fault::None);
  }
  EXPECT_TRUE(m.locked());
  const Nanos early = 14 * kMs + 200000;   // a frame 0.29 cycles after the previous one
  const MonitorReport r = m.on_edge(static_cast<std::uint64_t>(early), early);
  EXPECT_TRUE(r.cycle_too_small);
  EXPECT_EQ(r.fault, Fault::None);
}

TEST(SyncMonitor, Sm2CycleIsMeasuredWhenNotConfigured) {
  SyncMonitor m;
  MonitorConfig c;
  c.mode = SyncMode::Sm2Event;
  c.cycle = 0;
  c.lock_timeout = 1000 * kMs;
  c.lock_edges = 4;
  m.start(c, 0);
  for (int k = 0; k < 4; ++k) {
    const Nanos t = k * 3 * kMs;
    m.on_edge(static_cast<std::uint64_t>(t), t);
  }
  EXPECT_TRUE(m.locked());
  EXPECT_EQ(m.cycle(), 3 * kMs);
}

TEST(SyncMonitor, StopClearsDeadlines) {
  SyncMonitor m;
  m.start(dc_config(kMs), 0);
  EXPECT_LT(m.next_deadline(), std::numeric_limits<Nanos>::max());
  m.stop();
  EXPECT_FALSE(m.running());
  EXPECT_EQ(m.next_deadline(), std::numeric_limits<Nanos>::max());
  EXPECT_FALSE(m.on_edge(0, 0).run_cycle);
}

}  // namespace
}  // namespace vdrive::firmware::sync
