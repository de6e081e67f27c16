// Distributed clocks on a line of the three drives, each ESC with its own oscillator (drift,
// start offset), measured the way a master does it through frames: receive-time latch (BWR
// 0900h), propagation delays from the port receive times, offsets from 0918h, drift compensation
// with FRMW 0910h from the reference clock; then SYNC0 deadlines as the event loop sees them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::network {
namespace {

using test::ethercat_frame;
using test::first_data;
using test::first_wkc;

constexpr std::uint8_t kApwr = 0x02, kFprd = 0x04, kFpwr = 0x05, kBwr = 0x08, kFrmw = 0x0E;
constexpr Nanos kHop = 500;
constexpr Nanos kMs = 1000000;
constexpr std::uint64_t kMasterTime = 789'000'000'000'000ull;   // the master's clock at the latch

std::vector<std::uint8_t> le(std::uint64_t v, int bytes) {
  std::vector<std::uint8_t> out;
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  return out;
}
std::uint64_t get_le(const std::vector<std::uint8_t>& d, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes; i-- > 0;) v = (v << 8) | d[at + static_cast<std::size_t>(i)];
  return v;
}

class DcLine : public ::testing::Test {
protected:
  static NetworkOptions options() {
    NetworkOptions o;
    o.hop_delay = kHop;
    o.dc_models = {{+40.0, 0}, {-65.0, 7'300'000'123}, {+90.0, 123'456}};
    return o;
  }

  std::vector<std::uint8_t> exchange(std::uint8_t cmd, std::uint16_t adp, std::uint16_t ado,
                                     std::vector<std::uint8_t> data, std::uint16_t expect_wkc) {
    auto frame = ethercat_frame(cmd, adp, ado, data);
    EXPECT_TRUE(net_.process_frame(frame, clock_.now()));
    EXPECT_EQ(first_wkc(frame), expect_wkc) << "cmd " << int(cmd) << " ado " << std::hex << ado;
    return first_data(frame);
  }
  static std::uint16_t station(std::size_t i) { return static_cast<std::uint16_t>(0x1001 + i); }

  // The slave's local time at global time t, from the configured model (what the master should
  // find out without knowing it).
  static std::int64_t local_model(std::size_t i, Nanos t) {
    const DcModel m = options().dc_models[i];
    return m.start_offset + t + std::llround(static_cast<double>(t) * m.drift_ppm * 1e-6);
  }

  void SetUp() override {
    for (std::size_t i = 0; i < net_.size(); ++i)
      exchange(kApwr, static_cast<std::uint16_t>(-static_cast<int>(i)), 0x0010, le(station(i), 2), 1);
  }

  // SOEM ec_configdc, for a line: latch, delays, offsets, delays written.
  void configure_dc() {
    latch_time_ = clock_.now();
    exchange(kBwr, 0, 0x0900, le(0, 4), 3);
    clock_.advance(50000);
    std::vector<std::uint32_t> port_span(net_.size());
    for (std::size_t i = 0; i < net_.size(); ++i) {
      const auto rt = exchange(kFprd, station(i), 0x0900, std::vector<std::uint8_t>(16, 0), 1);
      const auto t0 = static_cast<std::uint32_t>(get_le(rt, 0, 4));
      const auto t1 = static_cast<std::uint32_t>(get_le(rt, 4, 4));
      port_span[i] = i + 1 < net_.size() ? t1 - t0 : 0;   // the last slave's port 1 is closed
      rt64_.push_back(get_le(exchange(kFprd, station(i), 0x0918, std::vector<std::uint8_t>(8, 0), 1), 0, 8));
    }
    delays_.assign(net_.size(), 0);
    for (std::size_t i = 1; i < net_.size(); ++i)
      delays_[i] = delays_[i - 1] + (static_cast<std::int64_t>(port_span[i - 1]) - port_span[i]) / 2;
    for (std::size_t i = 0; i < net_.size(); ++i) {
      offsets_.push_back(kMasterTime - rt64_[i]);
      exchange(kFpwr, station(i), 0x0920, le(offsets_[i], 8), 1);
      exchange(kFpwr, station(i), 0x0928, le(static_cast<std::uint64_t>(delays_[i]), 4), 1);
    }
  }

  // Cyclic drift compensation: the reference clock's system time to everybody, once per cycle.
  void compensate(Nanos duration, Nanos cycle = kMs) {
    const Nanos end = clock_.now() + duration;
    while (clock_.now() < end) {
      exchange(kFrmw, station(0), 0x0910, std::vector<std::uint8_t>(8, 0), 3);
      clock_.advance(cycle);
      net_.tick(clock_.now());   // the event loop runs due timers between frames
    }
  }

  // Each slave's system time minus the reference's, as the master measures it: one read per
  // slave at the same instant, each corrected by that slave's propagation delay.
  std::vector<std::int64_t> deviations() {
    std::vector<std::uint64_t> sys;
    for (std::size_t i = 0; i < net_.size(); ++i)
      sys.push_back(get_le(exchange(kFprd, station(i), 0x0910, std::vector<std::uint8_t>(8, 0), 1), 0, 8));
    std::vector<std::int64_t> dev;
    for (std::size_t i = 0; i < net_.size(); ++i)
      dev.push_back(static_cast<std::int64_t>(sys[i] - sys[0]) - delays_[i]);
    return dev;
  }

  VirtualClock clock_{2'000'000'000};
  Network net_{std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock_, options()};
  Nanos latch_time_ = 0;
  std::vector<std::uint64_t> rt64_;
  std::vector<std::int64_t> delays_;
  std::vector<std::uint64_t> offsets_;
};

TEST_F(DcLine, DelaysMeasuredFromPortReceiveTimesMatchTheLine) {
  configure_dc();
  for (std::size_t i = 0; i < net_.size(); ++i)
    EXPECT_NEAR(static_cast<double>(delays_[i]), static_cast<double>(i * kHop), 100.0) << "slave " << i;
}

TEST_F(DcLine, OffsetsMatchEachOscillatorsStartOffsetAndDrift) {
  configure_dc();
  for (std::size_t i = 0; i < net_.size(); ++i) {
    // The frame reached slave i i hops after the reference.
    const std::int64_t expected =
        static_cast<std::int64_t>(kMasterTime) - local_model(i, latch_time_ + static_cast<Nanos>(i) * kHop);
    EXPECT_NEAR(static_cast<double>(static_cast<std::int64_t>(offsets_[i])), static_cast<double>(expected), 100.0)
        << "slave " << i;
  }
}

TEST_F(DcLine, DriftCompensationKeepsEverySystemTimeWithin100nsOfTheReference) {
  configure_dc();
  compensate(3000 * kMs);
  for (int round = 0; round < 5; ++round) {
    const auto dev = deviations();
    for (std::size_t i = 1; i < net_.size(); ++i)
      EXPECT_LT(std::llabs(dev[i]), 100) << "slave " << i << " round " << round;
    // The ESC's own view: the filtered system time difference 092Ch.
    for (std::size_t i = 1; i < net_.size(); ++i) {
      const auto diff = get_le(exchange(kFprd, station(i), 0x092C, std::vector<std::uint8_t>(4, 0), 1), 0, 4);
      EXPECT_LT(diff & 0x7FFFFFFF, 100u) << "slave " << i;
    }
    compensate(200 * kMs);
  }
  // The reference clock runs at its own oscillator's rate: 40 ppm fast.
  const auto t0 = get_le(exchange(kFprd, station(0), 0x0910, std::vector<std::uint8_t>(8, 0), 1), 0, 8);
  clock_.advance(1000 * kMs);
  const auto t1 = get_le(exchange(kFprd, station(0), 0x0910, std::vector<std::uint8_t>(8, 0), 1), 0, 8);
  EXPECT_NEAR(static_cast<double>(t1 - t0), 1000 * kMs * (1 + 40e-6), 2.0);
}

TEST_F(DcLine, Sync0EdgesAreNetworkDeadlinesAtTheProgrammedSystemTimes) {
  configure_dc();
  compensate(2000 * kMs);
  const std::size_t slave = 2;   // the DS1000A: 90 ppm fast, 2 hops out
  const std::uint32_t cycle = 2000000;
  const auto now_sys = get_le(exchange(kFprd, station(slave), 0x0910, std::vector<std::uint8_t>(8, 0), 1), 0, 8);
  const std::uint64_t start = now_sys + 50 * kMs;
  exchange(kFpwr, station(slave), 0x0981, {0x00}, 1);
  exchange(kFpwr, station(slave), 0x09A0, le(cycle, 4), 1);
  exchange(kFpwr, station(slave), 0x0990, le(start, 8), 1);
  exchange(kFpwr, station(slave), 0x0981, {0x03}, 1);
  for (int k = 0; k < 20; ++k) {
    // The ESC's SYNC edge is one of the network's deadlines (the event loop waits for it).
    const Nanos deadline = net_.esc(slave).next_deadline();
    ASSERT_LT(deadline, std::numeric_limits<Nanos>::max());
    ASSERT_GE(deadline, clock_.now());
    ASSERT_LE(net_.next_deadline(), deadline);
    // Other timers due before the edge run first, as the event loop would run them.
    while (net_.next_deadline() < deadline) {
      clock_.set(std::max(clock_.now(), net_.next_deadline()));
      net_.tick(clock_.now());
    }
    clock_.set(deadline);
    net_.tick(deadline);
    EXPECT_GT(net_.esc(slave).next_deadline(), deadline);
    // At the deadline the slave's system time is at the pulse: read it through a frame (it
    // reaches the slave two hops later) and compare with the programmed grid.
    const auto sys = get_le(exchange(kFprd, station(slave), 0x0910, std::vector<std::uint8_t>(8, 0), 1), 0, 8);
    const std::int64_t expected = static_cast<std::int64_t>(start + static_cast<std::uint64_t>(k) * cycle) +
                                  static_cast<std::int64_t>(slave) * kHop;
    EXPECT_NEAR(static_cast<double>(static_cast<std::int64_t>(sys)), static_cast<double>(expected), 100.0)
        << "pulse " << k;
  }
}

}  // namespace
}  // namespace vdrive::network
