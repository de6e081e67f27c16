// Segment with a tree: a junction-like four-port ESC J with a branch on each of its ports 3, 1
// and 2, and one slave behind the branch on port 3:
//
//   master - J(0) -port 3- A(1) -port 1- D(4)
//             |  -port 1- B(2)
//             |  -port 2- C(3)
//
// The numbers are the order the slaves are given in; the frame visits them J, A, D, B, C (ESC
// port order 0 -> 3 -> 1 -> 2), which is what a master counts as positions. Frames are built
// byte by byte (test_frame.hpp) and read back as a master would.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "esc_model/esc.hpp"
#include "master/dc_topology.hpp"
#include "tests/network/test_frame.hpp"
#include "vdrive/network/segment.hpp"
#include "vdrive/network/topology.hpp"

namespace vdrive::network {
namespace {

using namespace test_frames;

constexpr std::size_t J = 0, A = 1, B = 2, C = 3, D = 4;
constexpr std::array<std::size_t, 5> kVisitingOrder = {J, A, D, B, C};

esc::EscConfig ports(std::uint8_t descriptor) {
  esc::EscConfig c;
  c.port_descriptor = descriptor;
  return c;
}

Topology junction_tree() {
  Topology t;
  t.uplinks = {Uplink{Uplink::kMaster, 0}, Uplink{int{J}, 3}, Uplink{int{J}, 1}, Uplink{int{J}, 2}, Uplink{int{A}, 1}};
  return t;
}

struct Tree : ::testing::Test {
  static constexpr Nanos kHop = 600;
  VirtualClock clock{1'000'000};
  std::vector<std::unique_ptr<esc::Esc>> escs;
  Segment segment{kHop};

  Tree() {
    escs.push_back(std::make_unique<esc::Esc>(ports(0xFF), clock));  // J: four MII ports
    for (int i = 0; i < 4; ++i) escs.push_back(std::make_unique<esc::Esc>(ports(0x0F), clock));  // ports 0, 1
    for (auto& e : escs) segment.append(*e);
    segment.set_topology(junction_tree());
  }
  Nanos send(TestFrame& f, bool expect_back = true) {
    clock.advance(10'000);
    EXPECT_EQ(segment.process(f.span(), clock.now()), expect_back);
    return clock.now();
  }
  static std::uint16_t station(std::size_t position) { return static_cast<std::uint16_t>(0x1001 + position); }
  // APWR station addresses by position, as a master does after counting slaves.
  void assign_addresses() {
    TestFrame f;
    for (std::size_t k = 0; k < escs.size(); ++k)
      f.add(APWR, static_cast<std::uint16_t>(-static_cast<int>(k)), 0x0010, le_bytes(station(k), 2));
    send(f);
  }
  std::uint64_t fprd(std::uint16_t address, std::uint16_t reg, int n) {
    TestFrame f;
    const std::size_t at = f.read(FPRD, address, reg, static_cast<std::size_t>(n));
    send(f);
    EXPECT_EQ(f.wkc(at, static_cast<std::size_t>(n)), 1) << "station " << address;
    return f.le(at, n);
  }
  std::uint16_t brd_wkc() {
    TestFrame f;
    const std::size_t at = f.read(BRD, 0, 0x0000, 1);
    send(f);
    return f.wkc(at, 1);
  }
  std::uint16_t peek16(std::size_t slave, std::uint16_t reg) const { return escs[slave]->peek_u16(reg); }
  // Latches every ESC's receive times (BWR 0x0900); returns when the frame reached J.
  Nanos latch() {
    TestFrame f;
    f.add(BWR, 0, 0x0900, le_bytes(0, 4));
    return send(f);
  }
};

TEST_F(Tree, PositionsFollowThePortOrderDepthFirst) {
  EXPECT_EQ(visiting_order(junction_tree(), 5), std::vector<std::size_t>(kVisitingOrder.begin(), kVisitingOrder.end()));
  TestFrame f;
  std::array<std::size_t, 5> at{};
  for (std::size_t k = 0; k < 5; ++k)
    at[k] = f.add(APWR, static_cast<std::uint16_t>(-static_cast<int>(k)), 0x0010, le_bytes(station(k), 2));
  send(f);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(f.wkc(at[k], 2), 1) << k;
    EXPECT_EQ(f.adp(at[k]), static_cast<std::uint16_t>(5 - k)) << "every ESC counted the address up";
    EXPECT_EQ(peek16(kVisitingOrder[k], 0x0010), station(k)) << "position " << k;
  }
  EXPECT_EQ(brd_wkc(), 5);
}

TEST_F(Tree, EachEscProcessesTheFrameOnceInVisitingOrder) {
  assign_addresses();
  // Every ESC holds its own mark in user RAM; an FRMW addressed to B (position 3) reads B's and
  // makes every other ESC write the datagram as it passes: those visited before B write what the
  // master sent, those after B write B's mark.
  for (std::size_t k = 0; k < 5; ++k) {
    TestFrame w;
    w.add(FPWR, station(k), 0x0F80, le_bytes(0xA0 + k, 1));
    send(w);
  }
  TestFrame f;
  const std::size_t at = f.add(FRMW, station(3), 0x0F80, le_bytes(0x5A, 1));
  send(f);
  EXPECT_EQ(f.wkc(at, 1), 5);  // read by one, written by four
  EXPECT_EQ(escs[J]->peek(0x0F80), 0x5A);
  EXPECT_EQ(escs[A]->peek(0x0F80), 0x5A);
  EXPECT_EQ(escs[D]->peek(0x0F80), 0x5A) << "D (behind port 3) comes before B (port 1)";
  EXPECT_EQ(escs[B]->peek(0x0F80), 0xA3);
  EXPECT_EQ(escs[C]->peek(0x0F80), 0xA3) << "C (port 2) comes after B (port 1)";
}

TEST_F(Tree, ReceiveTimesShowWhenTheFrameCameBackFromEachBranch) {
  // Every ESC's oscillator starts elsewhere: local time = offset + global time.
  for (std::size_t i = 0; i < escs.size(); ++i) escs[i]->set_dc_model(0.0, static_cast<Nanos>(1'000'000'000 * (i + 1)));
  assign_addresses();
  const Nanos t = latch();
  const Nanos h = kHop;
  // Global times at ports 0..3 (-1: the frame did not come back there).
  const std::array<std::array<Nanos, 4>, 5> expected = {{
      {t, t + 6 * h, t + 8 * h, t + 4 * h},  // J: out 3 (A, D), out 1 (B), out 2 (C)
      {t + h, t + 3 * h, -1, -1},            // A: out 1 (D)
      {t + 5 * h, -1, -1, -1},               // B
      {t + 7 * h, -1, -1, -1},               // C
      {t + 2 * h, -1, -1, -1},               // D
  }};
  for (std::size_t k = 0; k < 5; ++k) {
    const std::size_t slave = kVisitingOrder[k];
    const std::uint64_t all = fprd(station(k), 0x0900, 8);
    const std::uint64_t high = fprd(station(k), 0x0908, 8);
    const std::array<std::uint32_t, 4> rx = {static_cast<std::uint32_t>(all), static_cast<std::uint32_t>(all >> 32),
                                             static_cast<std::uint32_t>(high), static_cast<std::uint32_t>(high >> 32)};
    const auto offset = static_cast<std::uint64_t>(1'000'000'000 * (slave + 1));
    for (int p = 0; p < 4; ++p) {
      const Nanos want = expected[slave][static_cast<std::size_t>(p)];
      if (want < 0) EXPECT_EQ(rx[static_cast<std::size_t>(p)], 0u) << "slave " << slave << " port " << p << " never latched";
      else EXPECT_EQ(rx[static_cast<std::size_t>(p)], static_cast<std::uint32_t>(offset + static_cast<std::uint64_t>(want)))
          << "slave " << slave << " port " << p;
    }
  }
}

TEST_F(Tree, AMastersDelayComputationGivesEachSlaveItsCumulativeDelay) {
  for (std::size_t i = 0; i < escs.size(); ++i) escs[i]->set_dc_model(0.0, static_cast<Nanos>(7'000'000 * (i + 3)));
  assign_addresses();
  latch();
  // What the project master reads (master/dc_topology.hpp): DL status and the four receive times.
  std::vector<master::PortTimes> seen(escs.size());
  for (std::size_t k = 0; k < seen.size(); ++k) {
    seen[k].dl_status = static_cast<std::uint16_t>(fprd(station(k), 0x0110, 2));
    for (int p = 0; p < 4; ++p)
      seen[k].rx[static_cast<std::size_t>(p)] = static_cast<std::uint32_t>(fprd(station(k), static_cast<std::uint16_t>(0x0900 + 4 * p), 4));
  }
  const master::DcTopology m = master::compute_dc_topology(seen);
  // Positions J, A, D, B, C: the tree as cabled, and the time each was reached after J.
  EXPECT_EQ(m.parent, (std::vector<std::size_t>{0, 0, 1, 0, 0}));
  EXPECT_EQ(m.parent_port, (std::vector<int>{0, 3, 1, 1, 2}));
  EXPECT_EQ(m.delay, (std::vector<std::int64_t>{0, kHop, 2 * kHop, 5 * kHop, 7 * kHop}));
}

TEST_F(Tree, DlStatusShowsLinkAndLoopPerPortAndTheDescriptorThePorts) {
  assign_addresses();
  constexpr std::uint16_t kLinkAndLoop = 0xFFF0;  // bits 4-7 link, 8-15 loop closed / communication
  // J: link on all four ports, every loop open with communication.
  EXPECT_EQ(fprd(station(0), 0x0110, 2) & kLinkAndLoop, 0xAAF0u);
  // A: ports 0 and 1 linked and open; 2 and 3 not implemented: closed, no communication.
  EXPECT_EQ(fprd(station(1), 0x0110, 2) & kLinkAndLoop, 0x5A30u);
  // Leaves: port 0 only; port 1 closed for want of a link (auto).
  for (std::size_t k : {2u, 3u, 4u}) EXPECT_EQ(fprd(station(k), 0x0110, 2) & kLinkAndLoop, 0x5610u) << k;
  EXPECT_EQ(fprd(station(0), 0x0007, 1), 0xFFu);
  EXPECT_EQ(fprd(station(1), 0x0007, 1), 0x0Fu);
}

TEST_F(Tree, BrokenCableAtAPortDropsTheBranchBehindItAndHealingBringsItBack) {
  assign_addresses();
  ASSERT_TRUE(segment.set_port_cable(J, 3, false));  // J's port 3: A and D behind it
  EXPECT_FALSE(segment.port_cable_connected(J, 3));
  EXPECT_FALSE(segment.port_cable_connected(A, 0)) << "the same cable, named from its other end";
  EXPECT_EQ(brd_wkc(), 3);
  // J: port 3 without link, looped closed; the lost link is counted there.
  const std::uint16_t dl = peek16(J, 0x0110);
  EXPECT_EQ(dl & 0x0080, 0) << "no link on port 3";
  EXPECT_EQ((dl >> 14) & 0x03, 0x01) << "port 3 closed, no communication";
  EXPECT_EQ(escs[J]->peek(0x0313), 1);
  EXPECT_EQ(peek16(A, 0x0110) & 0x0010, 0) << "A sees no link at port 0";
  // Positions close up: B is now position 1.
  TestFrame f;
  const std::size_t at = f.read(APRD, static_cast<std::uint16_t>(-1), 0x0010, 2);
  send(f);
  EXPECT_EQ(f.le(at, 2), station(3));
  // The frame turns at J's port 3 at once: B is reached one hop after J.
  const Nanos t = latch();
  EXPECT_EQ(fprd(station(3), 0x0900, 4), static_cast<std::uint32_t>(t + kHop));
  EXPECT_EQ(fprd(station(0), 0x0904, 4), static_cast<std::uint32_t>(t + 2 * kHop));

  ASSERT_TRUE(segment.set_port_cable(J, 3, true));
  EXPECT_EQ(brd_wkc(), 5);
  EXPECT_EQ((peek16(J, 0x0110) >> 14) & 0x03, 0x02) << "port 3 open again (auto loop control)";

  // Deeper: the cable between A and D, named at A's port 1.
  ASSERT_TRUE(segment.set_port_cable(A, 1, false));
  EXPECT_EQ(brd_wkc(), 4);
  ASSERT_TRUE(segment.set_port_cable(A, 1, true));
  EXPECT_EQ(brd_wkc(), 5);
}

TEST_F(Tree, OnlyCabledPortsCanBeBrokenAndTheLineNumberingStillNamesTheCableIntoASlave) {
  EXPECT_FALSE(segment.set_port_cable(B, 1, false)) << "nothing behind B's port 1";
  EXPECT_FALSE(segment.set_port_cable(J, 4, false));
  EXPECT_FALSE(segment.set_port_cable(7, 0, false));
  EXPECT_EQ(segment.cabled_at(J, 2), int{C});
  EXPECT_EQ(segment.cabled_at(D, 0), int{D});
  EXPECT_EQ(segment.cabled_at(D, 1), -1);
  // set_cable(i) is the cable into slave i + 1, wherever that slave hangs: here D, behind A.
  segment.set_cable(int{D} - 1, false);
  EXPECT_FALSE(segment.port_cable_connected(A, 1));
  EXPECT_EQ(brd_wkc(), 4);
  segment.set_cable(int{D} - 1, true);
  segment.set_cable(-1, false);  // the master's cable into J: nothing comes back
  TestFrame f;
  f.read(BRD, 0, 0x0000, 1);
  send(f, /*expect_back=*/false);
  segment.set_cable(-1, true);
  EXPECT_EQ(brd_wkc(), 5);
}

TEST_F(Tree, PortClosedByDlControlIsSkippedAsALoopInsideTheEsc) {
  assign_addresses();
  TestFrame close;
  close.add(FPWR, station(0), 0x0101, le_bytes(0x0C, 1));  // DL control: J's port 1 closed
  send(close);
  EXPECT_EQ(brd_wkc(), 4) << "B is not reached";
  EXPECT_EQ((peek16(J, 0x0110) >> 10) & 0x03, 0x03) << "closed, link still there";
  const Nanos t = latch();
  EXPECT_EQ(fprd(station(4), 0x0900, 4), static_cast<std::uint32_t>(t + 5 * kHop)) << "C right after A's branch";
  TestFrame open;
  open.add(FPWR, station(0), 0x0101, le_bytes(0x00, 1));
  send(open);
  EXPECT_EQ(brd_wkc(), 5);
}

TEST_F(Tree, CorruptedFrameIsCountedAtEveryPortItPasses) {
  TestFrame f;
  f.read(BRD, 0, 0x0000, 1);
  segment.process_corrupted(f.span(), clock.now());
  // J finds the error (invalid frame, port 0) and marks it; it comes back marked through 3, 1, 2.
  EXPECT_EQ(escs[J]->peek(0x0300), 1);
  EXPECT_EQ(escs[J]->peek(0x0308), 0);
  for (const std::uint16_t forwarded_port : {0x0309, 0x030A, 0x030B}) EXPECT_EQ(escs[J]->peek(forwarded_port), 1) << forwarded_port;
  EXPECT_EQ(escs[A]->peek(0x0308), 1);
  EXPECT_EQ(escs[A]->peek(0x0309), 1);
  for (const std::size_t leaf : {B, C, D}) {
    EXPECT_EQ(escs[leaf]->peek(0x0308), 1) << leaf;
    EXPECT_EQ(escs[leaf]->peek(0x0309), 0) << leaf;
  }
}

// The line has its own walk (no tree bookkeeping); a chain cabled through other ports takes the
// tree's. Both must give the same positions, working counters and times.
TEST(TreeLine, AChainThroughPorts3And2IsTimedAsTheLine) {
  VirtualClock clock{1'000'000};
  std::vector<std::unique_ptr<esc::Esc>> escs;
  Segment line{600}, chain{600};
  for (int i = 0; i < 6; ++i) {
    escs.push_back(std::make_unique<esc::Esc>(ports(i < 3 ? 0x0F : 0xFF), clock));
    (i < 3 ? line : chain).append(*escs.back());
  }
  chain.set_topology(Topology{{Uplink{Uplink::kMaster, 0}, Uplink{0, 3}, Uplink{1, 2}}});
  const Topology spelled_out = Topology::line(3);
  EXPECT_TRUE(is_line(spelled_out));
  EXPECT_FALSE(is_line(Topology{{Uplink{Uplink::kMaster, 0}, Uplink{0, 3}, Uplink{1, 2}}}));
  for (Segment* s : {&line, &chain}) {
    TestFrame f;
    const std::size_t at = f.read(BRD, 0, 0x0000, 1);
    f.add(BWR, 0, 0x0900, le_bytes(0, 4));
    ASSERT_TRUE(s->process(f.span(), clock.now()));
    EXPECT_EQ(f.wkc(at, 1), 3);
  }
  // Port 0's time and the way out's (line: port 1; chain: port 3, then 2), read as a master would.
  for (int i = 0; i < 3; ++i) {
    std::array<std::uint64_t, 2> times{};
    for (Segment* s : {&line, &chain}) {
      TestFrame f;
      const std::size_t at = f.read(APRD, static_cast<std::uint16_t>(-i), 0x0900, 16);
      ASSERT_TRUE(s->process(f.span(), clock.now()));
      const int way_out = s == &line ? 1 : (i == 0 ? 3 : 2);
      EXPECT_EQ(f.wkc(at, 16), 1);
      times[s == &line ? 0 : 1] = f.le(at, 4) | f.le(at + static_cast<std::size_t>(4 * way_out), 4) << 32;
    }
    EXPECT_EQ(times[0], times[1]) << "slave " << i << ": port 0 and the way out";
  }
}

}  // namespace
}  // namespace vdrive::network
