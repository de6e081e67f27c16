// Datagram commands, addressing and working-counter rules; frame validation.
#include <gtest/gtest.h>

#include "ethercat/datagram.hpp"
#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

using namespace vdrive::ecat;

constexpr std::uint16_t kRam = 0x1000;

class LineTest : public ::testing::Test {
protected:
  LineTest() {
    for (auto& e : escs) e = std::make_unique<Esc>(default_config(), clock);
  }
  // Gives slave i station address 0x1001 + i through auto-increment addressing.
  void assign_stations() {
    for (std::uint16_t i = 0; i < 3; ++i) {
      const auto station = static_cast<std::uint16_t>(0x1001 + i);
      Result r = send(line(), cmd::APWR, Frame::ap(static_cast<std::uint16_t>(-i), 0x0010),
                      u16(station));
      ASSERT_EQ(r.wkc, 1);
    }
  }
  std::vector<Esc*> line() { return {escs[0].get(), escs[1].get(), escs[2].get()}; }

  VirtualClock clock;
  std::unique_ptr<Esc> escs[3];
};

TEST_F(LineTest, AutoIncrementAddressesSlaveByPositionAndEveryoneIncrementsAdp) {
  assign_stations();
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(escs[i]->peek(0x0010) | (escs[i]->peek(0x0011) << 8), 0x1001 + i);
  }
  Result r = send(line(), cmd::APRD, Frame::ap(0xFFFF, 0x0010), {0, 0});
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(r.data, u16(0x1002));
  EXPECT_EQ(r.adp, 0x0002);  // 0xFFFF incremented by three slaves
}

TEST_F(LineTest, AutoIncrementBeyondTheLineIsNotAnswered) {
  Result r = send(line(), cmd::APRD, Frame::ap(static_cast<std::uint16_t>(-3), 0x0000), {0});
  EXPECT_EQ(r.wkc, 0);
  EXPECT_EQ(r.data[0], 0);
  EXPECT_EQ(r.adp, 0);
}

TEST_F(LineTest, ApwrAndAprwCountAndSwapData) {
  Result w = send(line(), cmd::APWR, Frame::ap(0xFFFE, kRam), {1, 2, 3});
  EXPECT_EQ(w.wkc, 1);
  EXPECT_EQ(escs[2]->peek(kRam + 1), 2);
  EXPECT_EQ(escs[1]->peek(kRam + 1), 0);
  Result rw = send(line(), cmd::APRW, Frame::ap(0xFFFE, kRam), {7, 8, 9});
  EXPECT_EQ(rw.wkc, 3);
  EXPECT_EQ(rw.data, (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(escs[2]->peek(kRam), 7);
}

TEST_F(LineTest, ConfiguredAddressingMatchesStationOnly) {
  assign_stations();
  Result w = send(line(), cmd::FPWR, Frame::ap(0x1003, kRam), {0xAB});
  EXPECT_EQ(w.wkc, 1);
  EXPECT_EQ(escs[2]->peek(kRam), 0xAB);
  EXPECT_EQ(escs[0]->peek(kRam), 0);
  Result r = send(line(), cmd::FPRD, Frame::ap(0x1003, kRam), {0});
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(r.data[0], 0xAB);
  EXPECT_EQ(r.adp, 0x1003);  // configured addressing leaves ADP alone
  Result rw = send(line(), cmd::FPRW, Frame::ap(0x1003, kRam), {0xCD});
  EXPECT_EQ(rw.wkc, 3);
  EXPECT_EQ(rw.data[0], 0xAB);
  EXPECT_EQ(escs[2]->peek(kRam), 0xCD);
}

TEST_F(LineTest, ReadWriteCommandsWriteAtPhysicalReadWriteOffset) {
  assign_stations();
  ASSERT_EQ(send(line(), cmd::FPWR, Frame::ap(0x1001, 0x0108), u16(0x0010)).wkc, 1);
  escs[0]->pdi_write(kRam, std::vector<std::uint8_t>{0x44});
  Result rw = send(line(), cmd::FPRW, Frame::ap(0x1001, kRam), {0x66});
  EXPECT_EQ(rw.wkc, 3);
  EXPECT_EQ(rw.data[0], 0x44);
  EXPECT_EQ(escs[0]->peek(kRam), 0x44);
  EXPECT_EQ(escs[0]->peek(kRam + 0x10), 0x66);
}

TEST_F(LineTest, MismatchedAddressLeavesDataAndWkcUntouched) {
  assign_stations();
  Result r = send(line(), cmd::FPRD, Frame::ap(0x2222, 0x0000), {0x55}, 0);
  EXPECT_EQ(r.wkc, 0);
  EXPECT_EQ(r.data[0], 0x55);
  Result w = send(line(), cmd::FPWR, Frame::ap(0x2222, kRam), {0x55});
  EXPECT_EQ(w.wkc, 0);
  for (auto& e : escs) EXPECT_EQ(e->peek(kRam), 0);
}

TEST_F(LineTest, AliasAddressingOnlyWhenEnabledInDlControl) {
  assign_stations();
  // EEPROM word 4 loaded 0x1234 as alias into 0x0012 of every slave; give slave 1 its own.
  std::vector<std::uint8_t> alias = u16(0x0777);
  escs[1]->pdi_write(0x0012, alias);
  Result before = send(line(), cmd::FPRD, Frame::ap(0x0777, 0x0010), {0, 0});
  EXPECT_EQ(before.wkc, 0);
  Result enable = send(line(), cmd::FPWR, Frame::ap(0x1002, 0x0103), {0x01});
  ASSERT_EQ(enable.wkc, 1);
  Result after = send(line(), cmd::FPRD, Frame::ap(0x0777, 0x0010), {0, 0});
  EXPECT_EQ(after.wkc, 1);
  EXPECT_EQ(after.data, u16(0x1002));
  // The station address still answers too.
  EXPECT_EQ(send(line(), cmd::FPRD, Frame::ap(0x1002, 0x0010), {0, 0}).wkc, 1);
}

TEST_F(LineTest, BroadcastReadOrsDataOfAllSlavesAndIncrementsAdp) {
  escs[0]->pdi_write(0x0F80, std::vector<std::uint8_t>{0x01});
  escs[1]->pdi_write(0x0F80, std::vector<std::uint8_t>{0x10});
  escs[2]->pdi_write(0x0F80, std::vector<std::uint8_t>{0x80});
  Result r = send(line(), cmd::BRD, Frame::ap(0, 0x0F80), {0x02});
  EXPECT_EQ(r.wkc, 3);
  EXPECT_EQ(r.data[0], 0x93);
  EXPECT_EQ(r.adp, 3);
}

TEST_F(LineTest, BroadcastWriteReachesEverySlave) {
  Result r = send(line(), cmd::BWR, Frame::ap(0, kRam + 4), {0x42, 0x43});
  EXPECT_EQ(r.wkc, 3);
  for (auto& e : escs) EXPECT_EQ(e->peek(kRam + 5), 0x43);
}

TEST_F(LineTest, BroadcastReadWriteOrsReadDataAndWritesSentData) {
  escs[1]->pdi_write(0x0F80, std::vector<std::uint8_t>{0x0F});
  Result r = send(line(), cmd::BRW, Frame::ap(0, 0x0F80), {0x30});
  EXPECT_EQ(r.wkc, 9);
  // Slave 0 sees 0x30, reads 0x00; slave 1 sees 0x30 and ORs 0x0F; slave 2 writes 0x3F.
  EXPECT_EQ(r.data[0], 0x3F);
  EXPECT_EQ(escs[0]->peek(0x0F80), 0x30);
  EXPECT_EQ(escs[1]->peek(0x0F80), 0x30);
  EXPECT_EQ(escs[2]->peek(0x0F80), 0x3F);
}

TEST_F(LineTest, ArmwAddressedSlaveReadsOthersWrite) {
  escs[0]->pdi_write(0x0F80, std::vector<std::uint8_t>{0x11, 0x22});
  Result r = send(line(), cmd::ARMW, Frame::ap(0, 0x0F80), {0, 0});
  EXPECT_EQ(r.wkc, 3);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{0x11, 0x22}));
  EXPECT_EQ(escs[1]->peek(0x0F81), 0x22);
  EXPECT_EQ(escs[2]->peek(0x0F80), 0x11);
}

TEST_F(LineTest, FrmwAddressedSlaveReadsOthersWrite) {
  assign_stations();
  escs[1]->pdi_write(0x0F80, std::vector<std::uint8_t>{0x99});
  Result r = send(line(), cmd::FRMW, Frame::ap(0x1002, 0x0F80), {0x01});
  EXPECT_EQ(r.wkc, 3);
  EXPECT_EQ(r.data[0], 0x99);
  EXPECT_EQ(escs[0]->peek(0x0F80), 0x01);  // before the reader: writes what arrived
  EXPECT_EQ(escs[1]->peek(0x0F80), 0x99);
  EXPECT_EQ(escs[2]->peek(0x0F80), 0x99);
}

TEST_F(LineTest, NopAndReservedCommandsDoNothing) {
  for (std::uint8_t c : {cmd::NOP, std::uint8_t{0x0F}, std::uint8_t{0xFF}}) {
    Result r = send(line(), c, Frame::ap(0, kRam), {0x77});
    EXPECT_TRUE(r.passed);
    EXPECT_EQ(r.wkc, 0);
    EXPECT_EQ(r.adp, 0);
    EXPECT_EQ(r.data[0], 0x77);
    for (auto& e : escs) EXPECT_EQ(e->peek(kRam), 0);
  }
}

TEST_F(LineTest, SeveralDatagramsInOneFrameAreAllProcessed) {
  Frame f;
  const auto a = f.add(cmd::BWR, Frame::ap(0, kRam), {5});
  const auto b = f.add(cmd::BRD, Frame::ap(0, kRam), {0});
  const auto c = f.add(cmd::APRD, Frame::ap(0xFFFF, 0x0000), {0});
  for (auto& e : escs) ASSERT_TRUE(e->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(f.wkc(a), 3);
  EXPECT_EQ(f.wkc(b), 3);
  EXPECT_EQ(f.data(b)[0], 5);
  EXPECT_EQ(f.wkc(c), 1);
  EXPECT_EQ(f.data(c)[0], 0x04);  // ESC type of slave 1
}

TEST_F(LineTest, WorkingCounterWrapsAt16Bits) {
  Frame f;
  f.add(cmd::BRD, Frame::ap(0, 0x0000), {0}, 0xFFFF);
  ASSERT_TRUE(escs[0]->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(f.wkc(0), 0);
}

// ---- malformed frames ---------------------------------------------------------------------

class MalformedTest : public EscTest {
protected:
  std::uint8_t invalid_frames() const { return esc->peek(0x0300); }
};

TEST_F(MalformedTest, DatagramBeyondHeaderLengthIsRejectedAndCounted) {
  Frame f;
  f.add(cmd::BWR, Frame::ap(0, kRam), {1, 2, 3, 4});
  f.bytes()[0] = static_cast<std::uint8_t>(f.bytes()[0] - 1);  // header one byte short
  EXPECT_FALSE(esc->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(invalid_frames(), 1);
  EXPECT_EQ(esc->peek(kRam), 0);  // nothing of a bad frame is executed
  EXPECT_EQ(f.wkc(0), 0);
}

TEST_F(MalformedTest, HeaderLengthBeyondFrameIsRejected) {
  Frame f;
  f.add(cmd::BRD, Frame::ap(0, 0), {0});
  f.bytes().pop_back();  // truncated WKC
  EXPECT_FALSE(esc->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(invalid_frames(), 1);
}

TEST_F(MalformedTest, MoreBitPointingPastTheEndIsRejected) {
  Frame f;
  f.add(cmd::BWR, Frame::ap(0, kRam), {9});
  f.bytes()[2 + 7] |= 0x80;  // claims another datagram follows
  f.bytes().resize(f.bytes().size() + 20, 0);  // padding is not a datagram
  EXPECT_FALSE(esc->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(esc->peek(kRam), 0);
  EXPECT_EQ(invalid_frames(), 1);
}

TEST_F(MalformedTest, TooShortForAHeaderIsRejected) {
  std::vector<std::uint8_t> pdu = {0x0C};
  EXPECT_FALSE(esc->process_frame(pdu, FrameTiming{}));
  std::vector<std::uint8_t> empty_dlpdu = {0x00, 0x10};
  EXPECT_FALSE(esc->process_frame(empty_dlpdu, FrameTiming{}));
  EXPECT_EQ(invalid_frames(), 2);
}

TEST_F(MalformedTest, InvalidFrameCounterSaturatesAndWriteClearsAllCounters) {
  std::vector<std::uint8_t> bad = {0xFF, 0x17, 0x00};
  for (int i = 0; i < 300; ++i) EXPECT_FALSE(esc->process_frame(bad, FrameTiming{}));
  EXPECT_EQ(invalid_frames(), 0xFF);
  set_station();
  Result clear = fpwr(0x0305, {0});  // any counter clears them all
  EXPECT_EQ(clear.wkc, 1);
  EXPECT_EQ(invalid_frames(), 0);
}

TEST_F(MalformedTest, OtherFrameTypesPassUnchanged) {
  Frame f;
  f.add(cmd::BWR, Frame::ap(0, kRam), {1});
  f.bytes()[1] = static_cast<std::uint8_t>((f.bytes()[1] & 0x0F) | 0x40);  // type 4
  const std::vector<std::uint8_t> before = f.bytes();
  EXPECT_TRUE(esc->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(f.bytes(), before);
  EXPECT_EQ(esc->peek(kRam), 0);
  EXPECT_EQ(invalid_frames(), 0);
}

TEST_F(MalformedTest, UnpaddedAndPaddedFramesAreBothAccepted) {
  Frame shortest;
  shortest.add(cmd::BRD, Frame::ap(0, 0x0000), {0});  // 2 + 13 bytes, no Ethernet padding
  EXPECT_TRUE(esc->process_frame(shortest.pdu(), FrameTiming{}));
  EXPECT_EQ(shortest.wkc(0), 1);
  Frame padded;
  padded.add(cmd::BRD, Frame::ap(0, 0x0000), {0});
  padded.bytes().resize(46, 0xEE);
  EXPECT_TRUE(esc->process_frame(padded.pdu(), FrameTiming{}));
  EXPECT_EQ(padded.wkc(0), 1);
  EXPECT_EQ(invalid_frames(), 0);
}

TEST_F(MalformedTest, IrqFieldCarriesMaskedEcatEventRequest) {
  set_station();
  // The PDI writing AL status raises ECAT event "AL status" (bit 3).
  pdi_write(0x0130, u16(0x0002));
  Frame masked;
  masked.add(cmd::BRD, Frame::ap(0, 0x0000), {0}, 0, 0x8000);
  esc->process_frame(masked.pdu(), FrameTiming{});
  EXPECT_EQ(masked.irq(0), 0x8000);  // mask 0x0200 is 0: nothing added, master's bits kept
  EXPECT_EQ(fpwr(0x0200, u16(0x0008)).wkc, 1);
  Frame unmasked;
  unmasked.add(cmd::NOP, 0, {0});
  esc->process_frame(unmasked.pdu(), FrameTiming{});
  EXPECT_EQ(unmasked.irq(0), 0x0008);
  // The master reading AL status clears the event.
  EXPECT_EQ(fprd(0x0130, 2).data, u16(0x0002));
  Frame after;
  after.add(cmd::NOP, 0, {0});
  esc->process_frame(after.pdu(), FrameTiming{});
  EXPECT_EQ(after.irq(0), 0);
}

TEST(DatagramParse, ValidateCountsDatagramsThroughMoreBit) {
  Frame f;
  f.add(cmd::BRD, 0, {0, 0});
  f.add(cmd::LRW, 0x10000, {1, 2, 3, 4});
  f.add(cmd::NOP, 0, {});
  EXPECT_EQ(validate_dlpdu(f.pdu()), 3u);
  const EthercatHeader h = parse_ethercat_header(f.pdu());
  EXPECT_EQ(h.type, 1);
  EXPECT_EQ(h.length, f.bytes().size() - 2);
  DatagramView second(f.pdu().subspan(2 + 14));  // after BRD: 10 + 2 + 2 bytes
  EXPECT_EQ(second.command(), cmd::LRW);
  EXPECT_EQ(second.logical_address(), 0x10000u);
  EXPECT_EQ(second.length(), 4);
  EXPECT_TRUE(second.more());
  EXPECT_EQ(second.data()[3], 4);
}

TEST(DatagramParse, MaximumDatagramLengthIsElevenBits) {
  Frame f;
  f.add(cmd::NOP, 0, std::vector<std::uint8_t>(1486, 0));
  DatagramView d(f.pdu().subspan(2));
  EXPECT_EQ(d.length(), 1486);
  f.bytes()[2 + 7] |= 0x38;  // reserved bits 11-13 do not change the length
  EXPECT_EQ(d.length(), 1486);
  EXPECT_EQ(validate_dlpdu(f.pdu()), 1u);
}

}  // namespace
}  // namespace vdrive::esc::test
