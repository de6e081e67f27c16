// Segment's onward port: one line of three ESCs spread over two segments (two processes), the
// first two slaves here with port 1 of the second leading onward to a segment with the third.
// What a master sees must be what it sees of one line of three: auto-increment positions, working
// counters, station addresses, DL status and the receive times a delay measurement reads, with
// the time the frame spent beyond the seam showing where it was spent.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

#include "esc_model/esc.hpp"
#include "master/dc_topology.hpp"
#include "tests/network/test_frame.hpp"
#include "vdrive/network/segment.hpp"
#include "vdrive/network/topology.hpp"

namespace vdrive::network {
namespace {

using namespace test_frames;

constexpr Nanos kHop = 600;
// What the frame spends between leaving the first part and entering the second (the veth and
// the second process's wake-up), and between leaving the second and coming back.
constexpr Nanos kOut = 20'000;
constexpr Nanos kBack = 15'000;

esc::EscConfig ports(std::uint8_t descriptor) {
  esc::EscConfig c;
  c.port_descriptor = descriptor;
  return c;
}

struct SplitLine : ::testing::Test {
  VirtualClock clock{1'000'000};
  std::vector<std::unique_ptr<esc::Esc>> escs;  // by position: 0, 1 here; 2 beyond
  Segment here{kHop};
  Segment beyond{kHop};

  SplitLine() {
    for (int i = 0; i < 3; ++i) escs.push_back(std::make_unique<esc::Esc>(esc::EscConfig{}, clock));
    here.append(*escs[0]);
    here.append(*escs[1]);
    beyond.append(*escs[2]);
    here.set_onward_port();
    here.set_onward_link(true);
  }
  // The frame through both parts as the two event loops pass it; returns where it went in the
  // end (ToMaster after a round trip through the second part) and when it left each place.
  FrameExit send(TestFrame& f) {
    clock.advance(10'000);
    sent_at = clock.now();
    const FrameExit exit = here.route(f.span(), sent_at);
    if (exit != FrameExit::Onward) return exit;
    EXPECT_EQ(f[6] & 0x02, 0) << "the source MAC is marked by the root on the way back only";
    const FrameExit far = beyond.route(f.span(), sent_at + kHop + kOut);
    if (far != FrameExit::ToMaster) return far;
    returned_at = sent_at + kHop + kOut + kBack;
    EXPECT_TRUE(here.returned(f.span(), returned_at));
    return FrameExit::ToMaster;
  }
  std::uint64_t fprd(std::uint16_t station, std::uint16_t reg, int n) {
    TestFrame f;
    const std::size_t at = f.read(FPRD, station, reg, static_cast<std::size_t>(n));
    EXPECT_EQ(send(f), FrameExit::ToMaster);
    EXPECT_EQ(f.wkc(at, static_cast<std::size_t>(n)), 1) << "station " << station;
    return f.le(at, n);
  }
  void assign_addresses() {
    TestFrame f;
    for (int i = 0; i < 3; ++i) f.add(APWR, static_cast<std::uint16_t>(-i), 0x0010, le_bytes(0x1001 + i, 2));
    ASSERT_EQ(send(f), FrameExit::ToMaster);
  }
  std::vector<master::PortTimes> port_times() {
    std::vector<master::PortTimes> seen(3);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto station = static_cast<std::uint16_t>(0x1001 + k);
      seen[k].dl_status = static_cast<std::uint16_t>(fprd(station, 0x0110, 2));
      for (int p = 0; p < 4; ++p)
        seen[k].rx[static_cast<std::size_t>(p)] = static_cast<std::uint32_t>(fprd(station, static_cast<std::uint16_t>(0x0900 + 4 * p), 4));
    }
    return seen;
  }
  Nanos sent_at = 0;
  Nanos returned_at = 0;
};

TEST_F(SplitLine, AddressesAndWorkingCountersAreThoseOfOneLine) {
  TestFrame f;
  std::array<std::size_t, 3> at{};
  for (int i = 0; i < 3; ++i) at[i] = f.add(APWR, static_cast<std::uint16_t>(-i), 0x0010, le_bytes(0x1001 + i, 2));
  const std::size_t brd = f.read(BRD, 0, 0x0000, 1);
  ASSERT_EQ(send(f), FrameExit::ToMaster);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(f.wkc(at[i], 2), 1) << i;
    EXPECT_EQ(f.adp(at[i]), static_cast<std::uint16_t>(-i + 3)) << i;
    EXPECT_EQ(escs[static_cast<std::size_t>(i)]->peek_u16(0x0010), 0x1001 + i);
  }
  EXPECT_EQ(f.wkc(brd, 1), 3);
  EXPECT_EQ(f[6], 0x02);  // marked once, by the root, on the way back
  EXPECT_EQ(here.dropped(), 0u);
}

TEST_F(SplitLine, OnwardLinkDownClosesTheLineAtTheLastSlaveHere) {
  here.set_onward_link(false);
  TestFrame f;
  const std::size_t brd = f.read(BRD, 0, 0x0000, 1);
  ASSERT_EQ(send(f), FrameExit::ToMaster);
  EXPECT_EQ(f.wkc(brd, 1), 2);
  EXPECT_EQ(escs[1]->peek(0x0110) & 0x20, 0);  // DL status: no link on port 1
  here.set_onward_link(true);
  EXPECT_EQ(escs[1]->peek(0x0110) & 0x20, 0x20);
  TestFrame g;
  const std::size_t again = g.read(BRD, 0, 0x0000, 1);
  ASSERT_EQ(send(g), FrameExit::ToMaster);
  EXPECT_EQ(g.wkc(again, 1), 3);
}

TEST_F(SplitLine, APortClosedByDlControlKeepsTheFrameHere) {
  assign_addresses();
  TestFrame close;
  close.add(FPWR, 0x1002, 0x0100, le_bytes(0x0C00, 2));  // DL control: port 1 closed
  ASSERT_EQ(send(close), FrameExit::ToMaster);
  TestFrame f;
  const std::size_t brd = f.read(BRD, 0, 0x0000, 1);
  ASSERT_EQ(send(f), FrameExit::ToMaster);
  EXPECT_EQ(f.wkc(brd, 1), 2);
}

TEST_F(SplitLine, ReceiveTimesShowTheTimeBeyondTheSeamAndDelaysIncreaseAlongTheLine) {
  assign_addresses();
  TestFrame latch;
  latch.add(BWR, 0, 0x0900, le_bytes(0, 4));
  ASSERT_EQ(send(latch), FrameExit::ToMaster);
  const Nanos t0 = sent_at;
  const Nanos back = returned_at;
  const std::vector<master::PortTimes> seen = port_times();
  // Here: port 0 on the way out; port 1 when the frame came back through the seam.
  EXPECT_EQ(seen[0].rx[0], static_cast<std::uint32_t>(t0));
  EXPECT_EQ(seen[1].rx[0], static_cast<std::uint32_t>(t0 + kHop));
  EXPECT_EQ(seen[1].rx[1], static_cast<std::uint32_t>(back));
  EXPECT_EQ(seen[0].rx[1], static_cast<std::uint32_t>(back + kHop));
  // Beyond: its own port 0 when the frame got there (the last slave: port 1 closed).
  EXPECT_EQ(seen[2].rx[0], static_cast<std::uint32_t>(t0 + kHop + kOut));
  const master::DcTopology m = master::compute_dc_topology(seen);
  EXPECT_EQ(m.parent, (std::vector<std::size_t>{0, 0, 1}));
  ASSERT_EQ(m.delay.size(), 3u);
  EXPECT_EQ(m.delay[1], kHop);
  // Half the loop behind slave 2 (out, through slave 3, back), as a master computes it.
  EXPECT_EQ(m.delay[2], kHop + (kOut + kBack) / 2);
  EXPECT_LT(m.delay[0], m.delay[1]);
  EXPECT_LT(m.delay[1], m.delay[2]);
}

TEST_F(SplitLine, AFrameThatLatchedNothingLeavesTheReceiveTimesAlone) {
  assign_addresses();
  TestFrame latch;
  latch.add(BWR, 0, 0x0900, le_bytes(0, 4));
  ASSERT_EQ(send(latch), FrameExit::ToMaster);
  const std::uint64_t port1 = fprd(0x1002, 0x0904, 4);
  // Several frames through the seam since; none wrote 0x0900.
  for (int i = 0; i < 3; ++i) EXPECT_EQ(fprd(0x1002, 0x0904, 4), port1);
}

TEST_F(SplitLine, ACorruptFrameOrANonEtherCatFrameComingBackIsNotSent) {
  std::vector<std::uint8_t> junk(60, 0);
  junk[12] = 0x08;  // IPv4
  EXPECT_FALSE(here.returned(junk, clock.now()));
  Segment no_onward{kHop};
  esc::Esc lone(esc::EscConfig{}, clock);
  no_onward.append(lone);
  TestFrame f;
  f.read(BRD, 0, 0x0000, 1);
  EXPECT_FALSE(no_onward.returned(f.span(), clock.now()));
}

TEST(SegmentOnward, NeedsAPort1OnTheLastSlave) {
  VirtualClock clock{0};
  esc::Esc one_port(ports(0x03), clock);  // port 0 only
  Segment segment{kHop};
  segment.append(one_port);
  EXPECT_THROW(segment.set_onward_port(), std::invalid_argument);
  Segment empty{kHop};
  EXPECT_THROW(empty.set_onward_port(), std::invalid_argument);
}

// A tree here: J with A on port 3 and B on port 1; B is the last slave a frame visits, so its
// port 1 leads onward, and on the way back the frame passes B's port 1, then J's port 1.
TEST(SegmentOnward, InATreeTheLastVisitedSlaveGoesOnAndItsAncestorsLatchOnTheWayBack) {
  VirtualClock clock{1'000'000};
  esc::Esc j(ports(0xFF), clock), a(ports(0x0F), clock), b(ports(0x0F), clock), far(ports(0x0F), clock);
  Segment here{kHop};
  here.append(j);
  here.append(b);  // given before A: the visiting order, not the given order, decides
  here.append(a);
  Topology t;
  t.uplinks = {Uplink{Uplink::kMaster, 0}, Uplink{0, 1}, Uplink{0, 3}};
  here.set_topology(t);
  here.set_onward_port();
  EXPECT_EQ(here.onward_slave(), 1);  // B
  here.set_onward_link(true);
  Segment beyond{kHop};
  beyond.append(far);

  TestFrame f;
  f.add(BWR, 0, 0x0900, le_bytes(0, 4));
  const std::size_t brd = f.read(BRD, 0, 0x0000, 1);
  const Nanos t0 = 2'000'000;
  ASSERT_EQ(here.route(f.span(), t0), FrameExit::Onward);
  ASSERT_EQ(beyond.route(f.span(), t0 + 50'000), FrameExit::ToMaster);
  const Nanos back = t0 + 80'000;
  ASSERT_TRUE(here.returned(f.span(), back));
  EXPECT_EQ(f.wkc(brd, 1), 4);
  // Reads a receive time of the slave at `position` through both parts.
  const auto rx = [&](int position, int port) {
    TestFrame q;
    const std::size_t at = q.read(APRD, static_cast<std::uint16_t>(-position), static_cast<std::uint16_t>(0x0900 + 4 * port), 4);
    EXPECT_EQ(here.route(q.span(), t0 + 1'000'000), FrameExit::Onward);
    EXPECT_EQ(beyond.route(q.span(), t0 + 1'010'000), FrameExit::ToMaster);
    EXPECT_TRUE(here.returned(q.span(), t0 + 1'020'000));
    EXPECT_EQ(q.wkc(at, 4), 1) << "position " << position;
    return q.le(at, 4);
  };
  // Visiting order J, A, B: A at +1 hop, back into J's port 3 at +2, B at +3 hops; B's port 1
  // and J's port 1 when the frame came back through the seam, one hop apart.
  EXPECT_EQ(rx(0, 0), static_cast<std::uint64_t>(t0));
  EXPECT_EQ(rx(1, 0), static_cast<std::uint64_t>(t0 + kHop));
  EXPECT_EQ(rx(0, 3), static_cast<std::uint64_t>(t0 + 2 * kHop));
  EXPECT_EQ(rx(2, 0), static_cast<std::uint64_t>(t0 + 3 * kHop));
  EXPECT_EQ(rx(2, 1), static_cast<std::uint64_t>(back));
  EXPECT_EQ(rx(0, 1), static_cast<std::uint64_t>(back + kHop));
  EXPECT_EQ(rx(3, 0), static_cast<std::uint64_t>(t0 + 50'000));
}

}  // namespace
}  // namespace vdrive::network
