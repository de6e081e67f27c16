// DcUnit: receive-time latching, delay measurement, offset and drift compensation as a master
// performs them, SYNC0/SYNC1 generation against a virtual clock, register permissions.
#include "esc_model/dc_unit.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

namespace vdrive::esc {
namespace {

std::uint64_t rd(DcUnit& dc, std::uint16_t reg, int bytes, Nanos now) {
  std::array<std::uint8_t, 8> b{};
  dc.read(static_cast<std::uint16_t>(reg - 0x0900), std::span(b).first(bytes), now);
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | b[i];
  return v;
}

void wr(DcUnit& dc, std::uint16_t reg, std::uint64_t value, int bytes, Nanos now, bool ecat = true) {
  std::array<std::uint8_t, 8> b{};
  for (int i = 0; i < bytes; ++i) b[i] = static_cast<std::uint8_t>(value >> (8 * i));
  dc.write(static_cast<std::uint16_t>(reg - 0x0900), std::span(b).first(bytes), now, ecat);
}

std::int64_t sdiff(std::uint64_t a, std::uint64_t b) { return static_cast<std::int64_t>(a - b); }

TEST(DcUnit, LocalTimeFollowsOscillatorModel) {
  VirtualClock clock;
  DcUnit dc(clock);
  dc.set_start_offset(1'000'000);
  dc.set_drift_ppm(50.0);
  EXPECT_EQ(dc.local_time(0), 1'000'000u);
  EXPECT_EQ(dc.local_time(1'000'000'000), 1'000'000u + 1'000'000'000u + 50'000u);  // +50 us per s
  EXPECT_EQ(dc.system_time(1'000'000'000), dc.local_time(1'000'000'000));          // no offset yet
}

TEST(DcUnit, ResetValues) {
  VirtualClock clock;
  DcUnit dc(clock);
  EXPECT_EQ(rd(dc, 0x0930, 2, 0), 0x1000u);
  EXPECT_EQ(rd(dc, 0x0934, 1, 0), 0x04u);
  EXPECT_EQ(rd(dc, 0x0935, 1, 0), 0x0Cu);
  EXPECT_EQ(rd(dc, 0x0981, 1, 0), 0u);
  EXPECT_EQ(dc.next_deadline(), INT64_MAX);
}

TEST(DcUnit, LatchesReceiveTimesInLocalTime) {
  VirtualClock clock;
  DcUnit dc(clock);
  dc.set_start_offset(0x1'2345'0000);
  FrameTiming t;
  t.port0_rx = 10'000;
  t.port1_rx = 13'500;
  dc.latch_receive_times(t);
  EXPECT_EQ(rd(dc, 0x0900, 4, 20'000), static_cast<std::uint32_t>(0x1'2345'0000 + 10'000));
  EXPECT_EQ(rd(dc, 0x0904, 4, 20'000), static_cast<std::uint32_t>(0x1'2345'0000 + 13'500));
  EXPECT_EQ(rd(dc, 0x0918, 8, 20'000), 0x1'2345'0000u + 10'000u);  // full 64 bit at port 0
  // A closed port keeps what it had.
  FrameTiming t2;
  t2.port0_rx = 50'000;
  dc.latch_receive_times(t2);
  EXPECT_EQ(rd(dc, 0x0904, 4, 60'000), static_cast<std::uint32_t>(0x1'2345'0000 + 13'500));
  EXPECT_EQ(rd(dc, 0x0900, 4, 60'000), static_cast<std::uint32_t>(0x1'2345'0000 + 50'000));
}

TEST(DcUnit, OffsetAndDelayRegistersReadBackAndShiftSystemTime) {
  VirtualClock clock;
  DcUnit dc(clock);
  dc.set_start_offset(5'000);
  wr(dc, 0x0920, 0x0000'1000'0000'0000ull, 8, 0);
  wr(dc, 0x0928, 1234, 4, 0);
  EXPECT_EQ(rd(dc, 0x0920, 8, 0), 0x0000'1000'0000'0000ull);
  EXPECT_EQ(rd(dc, 0x0928, 4, 0), 1234u);
  EXPECT_EQ(dc.system_time(100), 0x0000'1000'0000'0000ull + 5'100u);
  EXPECT_EQ(rd(dc, 0x0910, 8, 100), dc.system_time(100));
}

TEST(DcUnit, PdiCannotWriteEcatRegisters) {
  VirtualClock clock;
  DcUnit dc(clock);
  wr(dc, 0x0920, 777, 8, 0, /*ecat=*/false);
  wr(dc, 0x09A0, 1'000'000, 4, 0, /*ecat=*/false);  // sync unit belongs to ECAT by default
  EXPECT_EQ(rd(dc, 0x0920, 8, 0), 0u);
  EXPECT_EQ(rd(dc, 0x09A0, 4, 0), 0u);
  wr(dc, 0x0980, 0x01, 1, 0);                        // hand the sync unit to the PDI
  wr(dc, 0x09A0, 1'000'000, 4, 0, /*ecat=*/false);
  wr(dc, 0x09A4, 5, 4, 0, /*ecat=*/true);           // now ECAT may not
  EXPECT_EQ(rd(dc, 0x09A0, 4, 0), 1'000'000u);
  EXPECT_EQ(rd(dc, 0x09A4, 4, 0), 0u);
}

// ---- a line of DC slaves, driven the way a master (SOEM / TwinCAT) sets up distributed clocks --

struct Line {
  static constexpr Nanos kHop = 700;
  VirtualClock clock{1'000'000};
  std::vector<std::unique_ptr<DcUnit>> dc;

  Line(std::initializer_list<std::pair<double, Nanos>> slaves) {
    for (const auto& [ppm, offset] : slaves) {
      dc.push_back(std::make_unique<DcUnit>(clock));
      dc.back()->set_drift_ppm(ppm);
      dc.back()->set_start_offset(offset);
    }
  }
  std::size_t n() const { return dc.size(); }
  Nanos port0(std::size_t i, Nanos t0) const { return t0 + static_cast<Nanos>(i) * kHop; }
  FrameTiming timing(std::size_t i, Nanos t0) const {
    FrameTiming t;
    t.port0_rx = port0(i, t0);
    if (i + 1 < n()) t.port1_rx = t0 + static_cast<Nanos>(2 * (n() - 1) - i) * kHop;
    return t;
  }

  // BWR 0x0900, then read port receive times: returns the measured propagation delay of each
  // slave from the reference (slave 0), as a master computes it.
  std::vector<std::int64_t> measure_delays() {
    const Nanos t0 = clock.now();
    for (std::size_t i = 0; i < n(); ++i) dc[i]->latch_receive_times(timing(i, t0));
    clock.advance(50'000);
    std::vector<std::int64_t> behind(n());
    for (std::size_t i = 0; i < n(); ++i) {
      const auto p0 = static_cast<std::uint32_t>(rd(*dc[i], 0x0900, 4, clock.now()));
      const auto p1 = static_cast<std::uint32_t>(rd(*dc[i], 0x0904, 4, clock.now()));
      behind[i] = i + 1 < n() ? static_cast<std::int32_t>(p1 - p0) : 0;  // port 1 closed at the end
    }
    std::vector<std::int64_t> delay(n());
    for (std::size_t i = 0; i < n(); ++i) delay[i] = (behind[0] - behind[i]) / 2;
    return delay;
  }

  // Offsets so that every system time equals the reference's (system time = reference local
  // time + master_offset), using the 0x0918 latch of the same frame, and the delays.
  void write_offsets_and_delays(const std::vector<std::int64_t>& delay, std::uint64_t master_offset) {
    const Nanos now = clock.now();
    const std::uint64_t ref_rx = rd(*dc[0], 0x0918, 8, now);
    for (std::size_t i = 0; i < n(); ++i) {
      const std::uint64_t rx = rd(*dc[i], 0x0918, 8, now);
      wr(*dc[i], 0x0920, ref_rx + master_offset + static_cast<std::uint64_t>(delay[i]) - rx, 8, now);
      wr(*dc[i], 0x0928, static_cast<std::uint64_t>(delay[i]), 4, now);
    }
  }

  // One FRMW 0x0910 frame: the reference reads its system time at its SOF, every other slave
  // gets that value written at its own SOF.
  void frmw(Nanos t0) {
    const std::uint64_t ref = rd(*dc[0], 0x0910, 8, port0(0, t0));
    for (std::size_t i = 1; i < n(); ++i) wr(*dc[i], 0x0910, ref, 8, port0(i, t0));
  }

  std::int64_t worst_deviation(Nanos at) const {
    std::int64_t worst = 0;
    for (std::size_t i = 1; i < n(); ++i)
      worst = std::max(worst, std::abs(sdiff(dc[i]->system_time(at), dc[0]->system_time(at))));
    return worst;
  }
};

TEST(DcLine, MeasuredDelaysMatchHopDelays) {
  Line line({{25.0, 7'000'000'000}, {-40.0, 123'456'789}, {80.0, 0xFFFF'FF00}});
  const auto delay = line.measure_delays();
  for (std::size_t i = 0; i < line.n(); ++i)
    EXPECT_NEAR(static_cast<double>(delay[i]), static_cast<double>(i * Line::kHop), 1.0) << "slave " << i;
}

TEST(DcLine, OffsetCompensationAlignsSystemTimes) {
  Line line({{0.0, 7'000'000'000}, {0.0, 123'456'789}, {0.0, 42}});
  line.write_offsets_and_delays(line.measure_delays(), 1'000'000'000'000ull);
  EXPECT_LE(line.worst_deviation(line.clock.now()), 1);
  EXPECT_NEAR(static_cast<double>(line.dc[0]->system_time(line.clock.now())),
              static_cast<double>(line.dc[0]->local_time(line.clock.now()) + 1'000'000'000'000ull), 1.0);
}

TEST(DcLine, DriftCompensationConverges) {
  Line line({{20.0, 7'000'000'000}, {-50.0, 123'456'789}, {90.0, 99}});
  line.write_offsets_and_delays(line.measure_delays(), 0);
  // Without compensation the clocks drift apart: 140 ppm over 100 ms = 14 us.
  EXPECT_GT(std::abs(sdiff(line.dc[2]->system_time(line.clock.now() + 100'000'000),
                           line.dc[1]->system_time(line.clock.now() + 100'000'000))),
            10'000);
  // Static drift compensation, then cyclic FRMW every 1 ms, as a master does.
  for (int k = 0; k < 3000; ++k) {
    line.clock.advance(k < 1000 ? 20'000 : 1'000'000);
    line.frmw(line.clock.now());
  }
  const Nanos t = line.clock.now();
  for (Nanos at : {t, t + 250'000, t + 500'000, t + 999'000}) EXPECT_LE(line.worst_deviation(at), 20) << at - t;
  // 0x092C: mean difference small; 0x0932: speed counter diff reflects the relative drift
  // (0.1 ppm per LSB): slave 1 runs 70 ppm slow relative to the reference, slave 2 70 ppm fast.
  for (std::size_t i = 1; i < line.n(); ++i) EXPECT_LE(rd(*line.dc[i], 0x092C, 4, t) & 0x7FFFFFFF, 10u);
  const auto speed1 = static_cast<std::int16_t>(rd(*line.dc[1], 0x0932, 2, t));
  const auto speed2 = static_cast<std::int16_t>(rd(*line.dc[2], 0x0932, 2, t));
  EXPECT_NEAR(speed1, 700, 5);
  EXPECT_NEAR(speed2, -700, 5);
}

TEST(DcUnit, SystemTimeDifferenceSignMeansLocalCopySmaller) {
  VirtualClock clock;
  DcUnit dc(clock);
  const Nanos now = 10'000;
  const std::uint64_t local = dc.system_time(now);
  wr(dc, 0x0934, 0, 1, now);          // no filtering: 0x092C shows the last difference
  wr(dc, 0x0910, local + 300, 4, now);  // reference is ahead: local copy smaller
  EXPECT_EQ(rd(dc, 0x092C, 4, now), 0x8000'0000u | 300u);
  wr(dc, 0x0910, local - 200, 4, now);  // reference behind: local copy greater
  EXPECT_EQ(rd(dc, 0x092C, 4, now), 200u);
  // Writing the speed counter start resets difference and speed counter diff.
  wr(dc, 0x0930, 0x1000, 2, now);
  EXPECT_EQ(rd(dc, 0x092C, 4, now), 0u);
  EXPECT_EQ(rd(dc, 0x0932, 2, now), 0u);
}

TEST(DcUnit, ControlLoopSlewsWithoutJumping) {
  VirtualClock clock;
  DcUnit dc(clock);
  const Nanos now = 10'000;
  const std::uint64_t before = dc.system_time(now);
  wr(dc, 0x0910, before + 1'000, 4, now);  // 1 us behind the reference
  EXPECT_EQ(dc.system_time(now), before);  // no jump
  // 1 ns per 1.28 us: after 640 us half of it is corrected, after 1.28 ms all of it.
  EXPECT_NEAR(sdiff(dc.system_time(now + 640'000), before), 640'000 + 500, 1);
  EXPECT_NEAR(sdiff(dc.system_time(now + 2'000'000), before), 2'000'000 + 1'000, 1);
}

// ---- SYNC generation ------------------------------------------------------------------------

struct SyncFixture : ::testing::Test {
  VirtualClock clock{5'000'000};
  DcUnit dc{clock};
  SyncFixture() {
    dc.set_start_offset(40'000'000'000);
    dc.set_drift_ppm(-30.0);
    dc.load_pulse_length(0);  // acknowledge mode
  }
  void program(std::uint64_t start, std::uint32_t cycle0, std::uint32_t cycle1, std::uint8_t activation) {
    wr(dc, 0x09A0, cycle0, 4, clock.now());
    wr(dc, 0x09A4, cycle1, 4, clock.now());
    wr(dc, 0x0990, start, 8, clock.now());
    wr(dc, 0x0981, activation, 1, clock.now());
  }
  // Runs the scheduler to the next deadline; returns the events and the system time then.
  std::pair<SyncEvents, std::uint64_t> step() {
    const Nanos d = dc.next_deadline();
    EXPECT_NE(d, INT64_MAX);
    EXPECT_GT(d, clock.now());
    clock.set(d);
    return {dc.tick(d), dc.system_time(d)};
  }
};

TEST_F(SyncFixture, Sync0FirstPulseAtStartTimeThenEveryCycle) {
  const std::uint64_t start = dc.system_time(clock.now()) + 300'000;
  program(start, 1'000'000, 0, 0x03);
  EXPECT_EQ(rd(dc, 0x0984, 1, clock.now()) & 0x01, 0x01u);  // first pulse pending
  EXPECT_EQ(rd(dc, 0x0990, 8, clock.now()), start);
  for (int k = 0; k < 20; ++k) {
    const auto [ev, sys] = step();
    EXPECT_TRUE(ev.sync0);
    EXPECT_FALSE(ev.sync1);
    EXPECT_GE(sys, start + k * 1'000'000ull);
    EXPECT_LE(sys, start + k * 1'000'000ull + 1);  // on the edge, within the 1 ns grid
    EXPECT_EQ(rd(dc, 0x0990, 8, clock.now()), start + (k + 1) * 1'000'000ull);
  }
  EXPECT_EQ(rd(dc, 0x0984, 1, clock.now()) & 0x01, 0u);
}

TEST_F(SyncFixture, NothingFiresBeforeTheEdge) {
  const std::uint64_t start = dc.system_time(clock.now()) + 300'000;
  program(start, 1'000'000, 0, 0x03);
  const Nanos d = dc.next_deadline();
  EXPECT_FALSE(dc.tick(d - 1).sync0);
  EXPECT_TRUE(dc.tick(d).sync0);
  EXPECT_FALSE(dc.tick(d).sync0);
}

// next_deadline() reuses its answer for one `now`; a write at that same `now` must still move it.
TEST_F(SyncFixture, DeadlineFollowsAWriteAtTheSameInstant) {
  const std::uint64_t start = dc.system_time(clock.now()) + 300'000;
  program(start, 1'000'000, 0, 0x03);
  const Nanos before = dc.next_deadline();
  EXPECT_EQ(dc.next_deadline(), before);
  // System time 50 us ahead: the edge, a system time, comes 50 us earlier in global time.
  wr(dc, 0x0920, 50'000, 8, clock.now());
  EXPECT_NEAR(static_cast<double>(dc.next_deadline()), static_cast<double>(before - 50'000), 1.0);
  wr(dc, 0x0981, 0x00, 1, clock.now());  // cyclic unit off: no edge at all
  EXPECT_EQ(dc.next_deadline(), INT64_MAX);
}

// With no drift and no correction the deadline is exactly the first host ns at which the system
// time reaches the edge, and next_deadline() keeps that answer as the clock moves towards it.
TEST(DcUnit, HostRateDeadlineIsTheFirstInstantAtTheEdge) {
  VirtualClock clock{5'000'000};
  DcUnit dc{clock};
  dc.set_start_offset(40'000'000'123);
  dc.load_pulse_length(0);
  wr(dc, 0x0920, 987'654'321, 8, clock.now());  // system time offset
  wr(dc, 0x09A0, 125'000u, 4, clock.now());
  wr(dc, 0x0990, dc.system_time(clock.now()) + 300'017, 8, clock.now());
  wr(dc, 0x0981, 0x03u, 1, clock.now());
  std::mt19937 rng(99);
  for (int k = 0; k < 2'000; ++k) {
    const Nanos d = dc.next_deadline();
    const std::uint64_t edge = rd(dc, 0x0990, 8, clock.now());
    ASSERT_EQ(dc.system_time(d), edge);
    ASSERT_EQ(dc.system_time(d - 1), edge - 1);
    for (int j = 0; j < 3 && clock.now() < d - 1; ++j) {
      clock.set(clock.now() + 1 + static_cast<Nanos>(rng() % static_cast<std::uint64_t>(d - 1 - clock.now())));
      ASSERT_EQ(dc.next_deadline(), d);
    }
    clock.set(d);
    ASSERT_TRUE(dc.tick(d).sync0);
  }
  // A drift makes it the general path's answer again, recomputed at every instant.
  dc.set_drift_ppm(50.0);
  const Nanos d = dc.next_deadline();
  const std::uint64_t edge = rd(dc, 0x0990, 8, clock.now());
  EXPECT_GE(dc.system_time(d), edge);
  EXPECT_LT(dc.system_time(d - 1), edge);
}

// A loop that gets to the edge late still asks for the deadline first: at host rate the answer is
// the edge's own instant, the same as a unit asked for the first time at that late moment gives.
TEST(DcUnit, HostRateDeadlineHoldsPastTheEdgeUntilTheUnitChanges) {
  auto program = [](DcUnit& dc, const VirtualClock& clock) {
    dc.set_start_offset(40'000'000'123);
    dc.load_pulse_length(0);
    wr(dc, 0x0920, 987'654'321, 8, clock.now());
    wr(dc, 0x09A0, 125'000u, 4, clock.now());
    wr(dc, 0x0990, dc.system_time(clock.now()) + 300'017, 8, clock.now());
    wr(dc, 0x0981, 0x03u, 1, clock.now());
  };
  VirtualClock clock{5'000'000};
  DcUnit dc{clock};
  program(dc, clock);
  const Nanos d = dc.next_deadline();
  for (const Nanos late : {Nanos{1}, Nanos{124'999}, Nanos{3'000'000}}) {
    clock.set(d + late);
    ASSERT_EQ(dc.next_deadline(), d) << late;
    VirtualClock fresh_clock{5'000'000};
    DcUnit fresh{fresh_clock};
    program(fresh, fresh_clock);
    fresh_clock.set(d + late);
    ASSERT_EQ(fresh.next_deadline(), d) << late;  // computed on the late path, not kept
  }
  ASSERT_TRUE(dc.tick(clock.now()).sync0);
  EXPECT_GT(dc.next_deadline(), d);  // the unit changed: the next edge
}

TEST_F(SyncFixture, AcknowledgeModeStatusClearsOnRead) {
  program(dc.system_time(clock.now()) + 1'000, 500'000, 0, 0x03);
  step();
  EXPECT_EQ(rd(dc, 0x098E, 1, clock.now()), 1u);
  EXPECT_EQ(rd(dc, 0x098E, 1, clock.now()), 0u);
}

TEST_F(SyncFixture, PulseLengthModeShowsSignalWhilePulseLasts) {
  dc.load_pulse_length(100);  // 1 us
  program(dc.system_time(clock.now()) + 1'000, 500'000, 0, 0x03);
  const auto [ev, sys] = step();
  ASSERT_TRUE(ev.sync0);
  EXPECT_EQ(rd(dc, 0x098E, 1, clock.now() + 500), 1u);
  EXPECT_EQ(rd(dc, 0x098E, 1, clock.now() + 500), 1u);  // not cleared by reading
  EXPECT_EQ(rd(dc, 0x098E, 1, clock.now() + 1'100), 0u);
}

TEST_F(SyncFixture, Sync1FollowsSync0ByItsCycleTime) {
  const std::uint64_t start = dc.system_time(clock.now()) + 100'000;
  program(start, 1'000'000, 200'000, 0x07);
  std::vector<std::pair<bool, std::uint64_t>> edges;  // (is_sync1, time relative to start)
  while (edges.size() < 6) {
    const auto [ev, sys] = step();
    if (ev.sync0) edges.emplace_back(false, sys - start);
    if (ev.sync1) edges.emplace_back(true, sys - start);
  }
  const std::vector<std::pair<bool, std::uint64_t>> want = {{false, 0}, {true, 200'000},       {false, 1'000'000},
                                                            {true, 1'200'000}, {false, 2'000'000}, {true, 2'200'000}};
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(edges[i].first, want[i].first) << i;
    EXPECT_NEAR(static_cast<double>(edges[i].second), static_cast<double>(want[i].second), 1.0) << i;
  }
}

TEST_F(SyncFixture, SingleShotWhenCycleTimeIsZero) {
  program(dc.system_time(clock.now()) + 10'000, 0, 0, 0x03);
  EXPECT_TRUE(step().first.sync0);
  EXPECT_EQ(dc.next_deadline(), INT64_MAX);
}

TEST_F(SyncFixture, StartTimeInThePastNeverFires) {
  program(dc.system_time(clock.now()) - 1'000, 1'000'000, 0, 0x03);
  EXPECT_EQ(dc.next_deadline(), INT64_MAX);
  clock.advance(10'000'000);
  EXPECT_FALSE(dc.tick(clock.now()).sync0);
  EXPECT_EQ(rd(dc, 0x0984, 1, clock.now()) & 0x01, 0x01u);  // still pending
}

TEST_F(SyncFixture, PlausibilityCheckStartsImmediatelyForPastStartTime) {
  const std::uint64_t now_sys = dc.system_time(clock.now());
  program(now_sys - 1'000, 1'000'000, 0, 0x23);
  EXPECT_EQ(rd(dc, 0x0984, 1, clock.now()) & 0x04, 0x04u);
  EXPECT_TRUE(dc.tick(clock.now()).sync0);
  EXPECT_EQ(rd(dc, 0x0990, 8, clock.now()), now_sys + 1'000'000);
}

TEST_F(SyncFixture, AutoActivationByWritingStartTime) {
  wr(dc, 0x09A0, 250'000, 4, clock.now());
  wr(dc, 0x0981, 0x0A, 1, clock.now());  // SYNC0 + auto-activation, not yet active
  EXPECT_EQ(dc.next_deadline(), INT64_MAX);
  const std::uint64_t start = dc.system_time(clock.now()) + 50'000;
  wr(dc, 0x0990, start, 8, clock.now());
  EXPECT_EQ(rd(dc, 0x0981, 1, clock.now()) & 0x01, 0x01u);
  const auto [ev, sys] = step();
  EXPECT_TRUE(ev.sync0);
  EXPECT_NEAR(static_cast<double>(sys), static_cast<double>(start), 1.0);
}

TEST_F(SyncFixture, DeactivationStopsPulses) {
  program(dc.system_time(clock.now()) + 10'000, 100'000, 0, 0x03);
  step();
  wr(dc, 0x0981, 0x00, 1, clock.now());
  EXPECT_EQ(dc.next_deadline(), INT64_MAX);
  clock.advance(1'000'000);
  EXPECT_FALSE(dc.tick(clock.now()).sync0);
}

TEST_F(SyncFixture, LateTickMergesMissedPulsesAndStaysOnTheGrid) {
  const std::uint64_t start = dc.system_time(clock.now()) + 10'000;
  program(start, 100'000, 0, 0x03);
  clock.advance(1'000'000);  // ~10 cycles late
  EXPECT_TRUE(dc.tick(clock.now()).sync0);
  const std::uint64_t next = rd(dc, 0x0990, 8, clock.now());
  EXPECT_EQ((next - start) % 100'000, 0u);
  EXPECT_GT(next, dc.system_time(clock.now()));
  EXPECT_LE(next - dc.system_time(clock.now()), 100'000u);
}

TEST_F(SyncFixture, FarFutureStartTimeHasNoDeadline) {
  program(0xFFFF'FFFF'FFFF'0000ull, 1'000'000, 500, 0x07);
  EXPECT_EQ(dc.next_deadline(), INT64_MAX);
  EXPECT_FALSE(dc.tick(clock.now()).sync1);
}

// Whatever a master or firmware writes, the unit answers and keeps its invariants.
// A real clock moves between any two readings. The event loop reads `now`, then asks for the next
// deadline and ticks when `deadline <= now`: an edge that is already due must therefore report a
// deadline no later than any earlier reading, or the loop waits forever and SYNC0 never fires
// (found with SOEM-style DC start-up over a real veth: the servos fell back with 0x002D).
class TickingClock final : public Clock {
public:
  Nanos now() const override { return t_ += 250; }   // 250 ns pass with every reading
  mutable Nanos t_ = 1'000'000;
};

TEST(DcUnit, DueEdgeReportsADeadlineNotLaterThanAnEarlierClockReading) {
  TickingClock clock;
  DcUnit dc{clock};
  dc.load_pulse_length(0);
  const std::uint64_t start = dc.system_time(clock.now()) + 100'000;
  wr(dc, 0x09A0, 1'000'000u, 4, clock.now());
  wr(dc, 0x0990, start, 8, clock.now());
  wr(dc, 0x0981, 0x03u, 1, clock.now());

  clock.t_ += 200'000;  // the start time has passed
  int fired = 0;
  for (int loop = 0; loop < 5 && fired == 0; ++loop) {
    const Nanos now = clock.now();          // as the event loop does: read the time first...
    const Nanos deadline = dc.next_deadline();
    ASSERT_NE(deadline, INT64_MAX);
    EXPECT_LE(deadline, now);               // ...then the due edge must count as due
    if (deadline <= now && dc.tick(now).sync0) ++fired;
  }
  EXPECT_EQ(fired, 1);
}

TEST(DcUnit, RandomRegisterTrafficKeepsInvariants) {
  VirtualClock clock;
  DcUnit dc(clock);
  dc.set_drift_ppm(77.0);
  std::mt19937 rng(12345);
  std::array<std::uint8_t, 16> buf{};
  for (int i = 0; i < 20'000; ++i) {
    clock.advance(static_cast<Nanos>(rng() % 50'000));
    const auto offset = static_cast<std::uint16_t>(rng() % 0x100);
    const std::size_t len = 1 + rng() % std::min<std::size_t>(buf.size(), 0x100 - offset);
    for (auto& b : buf) b = static_cast<std::uint8_t>(rng());
    if (rng() % 2) {
      dc.write(offset, std::span(buf).first(len), clock.now(), rng() % 4 != 0);
    } else {
      dc.read(offset, std::span(buf).first(len), clock.now());
    }
    dc.tick(clock.now());
    const Nanos d = dc.next_deadline();
    ASSERT_TRUE(d == INT64_MAX || d > clock.now());
    ASSERT_EQ(rd(dc, 0x0931, 1, clock.now()) & 0x80, 0u);  // speed counter start is 15 bit
  }
}

}  // namespace
}  // namespace vdrive::esc
