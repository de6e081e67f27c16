// Segment: a line of real Esc instances. Frames are built here byte by byte (independent of the
// master library) and read back as a master would.
#include "vdrive/network/segment.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "esc_model/esc.hpp"
#include "tests/network/test_frame.hpp"

namespace vdrive::network {
namespace {

using namespace test_frames;

struct Line : ::testing::Test {
  static constexpr Nanos kHop = 600;
  VirtualClock clock{1'000'000};
  std::vector<std::unique_ptr<esc::Esc>> escs;
  Segment segment{kHop};

  Line() {
    for (int i = 0; i < 3; ++i) {
      escs.push_back(std::make_unique<esc::Esc>(esc::EscConfig{}, clock));
      segment.append(*escs.back());
    }
  }
  bool send(TestFrame& f) {
    clock.advance(10'000);
    return segment.process(f.span(), clock.now());
  }
  // APWR station addresses 0x1001.. by position, as a master does after counting slaves.
  void assign_addresses() {
    TestFrame f;
    for (int i = 0; i < 3; ++i)
      f.add(APWR, static_cast<std::uint16_t>(-i), 0x0010, le_bytes(0x1001 + i, 2));
    ASSERT_TRUE(send(f));
  }
  std::uint64_t fprd(std::uint16_t station, std::uint16_t reg, int n) {
    TestFrame f;
    const std::size_t at = f.read(FPRD, station, reg, static_cast<std::size_t>(n));
    EXPECT_TRUE(send(f));
    EXPECT_EQ(f.wkc(at, static_cast<std::size_t>(n)), 1);
    return f.le(at, n);
  }
  std::uint16_t brd_wkc() {
    TestFrame f;
    const std::size_t at = f.read(BRD, 0, 0x0000, 1);
    if (!send(f)) return 0xFFFF;
    return f.wkc(at, 1);
  }
};

TEST_F(Line, AutoIncrementAddressesFollowCableOrder) {
  TestFrame f;
  std::array<std::size_t, 3> at{};
  for (int i = 0; i < 3; ++i) at[i] = f.add(APWR, static_cast<std::uint16_t>(-i), 0x0010, le_bytes(0x1001 + i, 2));
  ASSERT_TRUE(send(f));
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(f.wkc(at[i], 2), 1) << i;
    EXPECT_EQ(f.adp(at[i]), static_cast<std::uint16_t>(-i + 3)) << i;  // every slave incremented it
    EXPECT_EQ(escs[i]->peek(0x0010) | (escs[i]->peek(0x0011) << 8), 0x1001 + i);
  }
}

TEST_F(Line, BroadcastReachesEverySlaveAndSourceMacGetsBit1) {
  TestFrame f;
  const std::size_t at = f.read(BRD, 0, 0x0000, 1);
  ASSERT_TRUE(send(f));
  EXPECT_EQ(f.wkc(at, 1), 3);
  EXPECT_EQ(f[6], 0x02);  // source MAC first byte: locally administered bit set on the way back
  EXPECT_EQ(f[7], 0x11);
  EXPECT_EQ(f[0], 0xFF);  // destination untouched
}

TEST_F(Line, VlanTaggedFramesAreProcessed) {
  TestFrame f(/*vlan=*/true);
  const std::size_t at = f.read(BRD, 0, 0x0000, 1);
  ASSERT_TRUE(send(f));
  EXPECT_EQ(f.wkc(at, 1), 3);
}

TEST_F(Line, NonEtherCatAndMalformedFramesAreDropped) {
  TestFrame ip;
  ip.read(BRD, 0, 0, 1);
  ip[12] = 0x08;
  ip[13] = 0x00;
  EXPECT_FALSE(send(ip));
  std::array<std::uint8_t, 10> runt{};
  EXPECT_FALSE(segment.process(runt, clock.now()));
  TestFrame bad;
  const std::size_t at = bad.read(BRD, 0, 0, 1);
  bad[at - 4] = 0xFF;  // datagram length beyond the frame
  EXPECT_FALSE(send(bad));
  EXPECT_EQ(segment.dropped(), 3u);
  EXPECT_EQ(brd_wkc(), 3);  // the line still works
}

TEST_F(Line, CableBreakLoopsBackEarlyAndUpdatesLinks) {
  segment.set_cable(0, false);  // between slave 1 and slave 2
  EXPECT_FALSE(segment.cable_connected(0));
  EXPECT_EQ(brd_wkc(), 1);
  // DL status 0x0110: link bits 4+p.
  EXPECT_EQ(escs[0]->peek(0x0110) & 0x30, 0x10);  // port 0 link, port 1 none
  EXPECT_EQ(escs[1]->peek(0x0110) & 0x30, 0x20);  // port 1 link, port 0 none
  EXPECT_FALSE(escs[0]->port_forwards(1));

  segment.set_cable(0, true);
  EXPECT_EQ(brd_wkc(), 3);

  segment.set_cable(-1, false);  // master to slave 1: nothing comes back
  EXPECT_EQ(brd_wkc(), 0xFFFF);
  segment.set_cable(-1, true);
  EXPECT_EQ(brd_wkc(), 3);
}

TEST_F(Line, PortClosedByDlControlTurnsTheFrame) {
  assign_addresses();
  TestFrame close;
  close.add(FPWR, 0x1002, 0x0101, le_bytes(0x0C, 1));  // DL control: port 1 closed
  ASSERT_TRUE(send(close));
  EXPECT_EQ(brd_wkc(), 2);
}

TEST_F(Line, ReceiveTimesGiveHopDelaysAsAMasterMeasuresThem) {
  assign_addresses();
  TestFrame latch;
  latch.add(BWR, 0, 0x0900, le_bytes(0, 4));
  ASSERT_TRUE(send(latch));
  const Nanos rx = clock.now();
  std::array<std::int64_t, 3> behind{};
  for (int i = 0; i < 3; ++i) {
    const auto station = static_cast<std::uint16_t>(0x1001 + i);
    const auto p0 = static_cast<std::uint32_t>(fprd(station, 0x0900, 4));
    const auto p1 = static_cast<std::uint32_t>(fprd(station, 0x0904, 4));
    // DL status: a master only trusts port 1's time if port 1 has communication.
    const std::uint64_t dl_status = fprd(station, 0x0110, 2);  // port 1: bit 10 closed, bit 11 comm.
    const bool port1_open = (dl_status & 0x0800) != 0 && (dl_status & 0x0400) == 0;
    behind[i] = port1_open ? static_cast<std::int32_t>(p1 - p0) : 0;
    EXPECT_EQ(p0, static_cast<std::uint32_t>(rx + i * kHop)) << i;  // local = global here (no drift)
  }
  for (int i = 0; i < 3; ++i) {
    const double delay = static_cast<double>(behind[0] - behind[i]) / 2.0;
    EXPECT_NEAR(delay, static_cast<double>(i * kHop), 1.0) << i;
  }
  EXPECT_EQ(behind[0], 4 * kHop);  // out to slave 3 and back
}

TEST_F(Line, OffsetDelayAndFrmwAlignSystemTimes) {
  assign_addresses();
  TestFrame latch;
  latch.add(BWR, 0, 0x0900, le_bytes(0, 4));
  ASSERT_TRUE(send(latch));
  const std::uint64_t ref_rx = fprd(0x1001, 0x0918, 8);
  for (int i = 0; i < 3; ++i) {
    const auto station = static_cast<std::uint16_t>(0x1001 + i);
    const std::uint64_t rx = fprd(station, 0x0918, 8);
    const std::uint64_t delay = static_cast<std::uint64_t>(i * kHop);
    TestFrame w;
    w.add(FPWR, station, 0x0920, le_bytes(ref_rx + delay - rx + 5'000'000'000ull, 8));
    w.add(FPWR, station, 0x0928, le_bytes(delay, 4));
    ASSERT_TRUE(send(w));
  }
  for (int k = 0; k < 100; ++k) {
    TestFrame f;
    const std::size_t at = f.read(FRMW, 0x1001, 0x0910, 8);
    ASSERT_TRUE(send(f));
    EXPECT_EQ(f.wkc(at, 8), 3);  // read at the reference, written at the two others
  }
  // Read all three system times in one frame: each latches at its own SOF, so the values
  // differ by exactly the propagation delay.
  TestFrame f;
  std::array<std::size_t, 3> at{};
  for (int i = 0; i < 3; ++i) at[i] = f.read(FPRD, static_cast<std::uint16_t>(0x1001 + i), 0x0910, 8);
  ASSERT_TRUE(send(f));
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(static_cast<double>(f.le(at[i], 8) - f.le(at[0], 8)), static_cast<double>(i * kHop), 2.0) << i;
  EXPECT_GT(f.le(at[0], 8), 5'000'000'000ull);
}

// A frame with a bad FCS (fault::WireImpairment corrupt): slave 1 counts an invalid frame at
// port 0, the slaves behind it forwarded errors at port 0 and, on the way back, at port 1; the
// master gets nothing. With the line cut after slave 1 only slave 1 sees it.
void corrupted(Segment& segment) {
  TestFrame f;
  f.read(BRD, 0, 0x0000, 1);
  segment.process_corrupted(f.span(), 0);
}

TEST_F(Line, CorruptedFrameIsCountedWhereItEntersAndAsForwardedBehind) {
  assign_addresses();
  const std::uint64_t dropped = segment.dropped();
  corrupted(segment);
  EXPECT_EQ(segment.dropped(), dropped + 1);
  // 0x0300 invalid frame port 0, 0x0302 port 1, 0x0308 forwarded port 0, 0x0309 port 1.
  EXPECT_EQ(fprd(0x1001, 0x0300, 1), 1u);
  EXPECT_EQ(fprd(0x1001, 0x0308, 1), 0u);
  EXPECT_EQ(fprd(0x1001, 0x0309, 1), 1u) << "the marked frame came back through port 1";
  EXPECT_EQ(fprd(0x1002, 0x0300, 1), 0u);
  EXPECT_EQ(fprd(0x1002, 0x0308, 1), 1u);
  EXPECT_EQ(fprd(0x1002, 0x0309, 1), 1u);
  EXPECT_EQ(fprd(0x1003, 0x0308, 1), 1u);
  EXPECT_EQ(fprd(0x1003, 0x0309, 1), 0u) << "the last slave turns it: nothing at port 1";
  EXPECT_EQ(fprd(0x1003, 0x0302, 1), 0u);

  segment.set_cable(0, false);
  corrupted(segment);
  EXPECT_EQ(fprd(0x1001, 0x0300, 1), 2u);
  EXPECT_EQ(fprd(0x1001, 0x0309, 1), 1u) << "port 1 closed: turned inside slave 1";
  segment.set_cable(0, true);
  EXPECT_EQ(fprd(0x1002, 0x0308, 1), 1u);

  segment.set_cable(-1, false);
  corrupted(segment);  // cut before slave 1: nobody counts
  segment.set_cable(-1, true);
  EXPECT_EQ(fprd(0x1001, 0x0300, 1), 2u);
}

}  // namespace
}  // namespace vdrive::network
