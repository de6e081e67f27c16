// Register reset values, per-side write permissions, side effects, EEPROM load, DL status.
#include <gtest/gtest.h>

#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

class RegistersTest : public EscTest {
protected:
  void SetUp() override { set_station(); }
};

TEST_F(RegistersTest, IdentityComesFromConfigAndIsReadOnly) {
  Result r = fprd(0x0000, 10);
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{0x04, 0x02, 0x44, 0x00, 0x03, 0x04, 0x08, 0x0F,
                                               0x8C, 0x01}));
  Result w = fpwr(0x0000, {0xFF, 0xFF});
  EXPECT_EQ(w.wkc, 1);  // the access is acknowledged, the register keeps its value
  EXPECT_EQ(esc->peek(0x0000), 0x04);
  pdi_write(0x0004, {0x10});
  EXPECT_EQ(esc->peek(0x0004), 0x03);
}

TEST_F(RegistersTest, ResetValues) {
  EXPECT_EQ(peek32(0x0204), 0x00FFFF0Fu);
  EXPECT_EQ(peek16(0x0400), 0x09C2);
  EXPECT_EQ(peek16(0x0410), 0x03E8);
  EXPECT_EQ(peek16(0x0420), 0x03E8);
  EXPECT_EQ(peek16(0x0120), 0x0001);
  EXPECT_EQ(peek16(0x0130), 0x0001);
  EXPECT_EQ(peek16(0x0134), 0x0000);
  EXPECT_EQ(peek32(0x0220), 0u);
  EXPECT_EQ(peek32(0x0100) & 0x01000000u, 0u);  // alias disabled
}

TEST_F(RegistersTest, EepromConfigurationAreaIsLoadedAtPowerOn) {
  EXPECT_EQ(peek16(0x0140), 0x0C05);
  EXPECT_EQ(peek16(0x0150), 0x6603);
  EXPECT_EQ(peek16(0x0152), 0x0000);
  EXPECT_EQ(peek16(0x0012), 0x1234);
  EXPECT_EQ(fprd(0x0110, 2).data[0] & 0x01, 0x01);  // PDI operational
}

TEST(RegistersEeprom, InvalidConfigurationAreaLeavesPdiNotOperational) {
  VirtualClock clock;
  EscConfig config;
  config.sii_image = sii_image(0x4321);
  config.sii_image[14] ^= 0xFF;  // break the CRC
  Esc esc(config, clock);
  EXPECT_EQ(esc.peek(0x0110) & 0x01, 0);
  EXPECT_EQ(esc.peek(0x0012), 0);
}

TEST_F(RegistersTest, StationAddressEcatWritablePdiReadOnly) {
  EXPECT_EQ(peek16(0x0010), 0x1001);
  pdi_write(0x0010, u16(0x2222));
  EXPECT_EQ(pdi16(0x0010), 0x1001);
  EXPECT_EQ(fprd(0x0010, 2).data, u16(0x1001));
}

TEST_F(RegistersTest, AliasPdiWritableEcatReadOnly) {
  fpwr(0x0012, u16(0x5555));
  EXPECT_EQ(peek16(0x0012), 0x1234);
  pdi_write(0x0012, u16(0x5555));
  EXPECT_EQ(fprd(0x0012, 2).data, u16(0x5555));
}

TEST_F(RegistersTest, AlStatusAndCodeWrittenByPdiOnly) {
  fpwr(0x0130, u16(0x0008));
  fpwr(0x0134, u16(0x0011));
  EXPECT_EQ(peek16(0x0130), 0x0001);
  EXPECT_EQ(peek16(0x0134), 0x0000);
  pdi_write(0x0130, u16(0x0012));
  pdi_write(0x0134, u16(0x0011));
  EXPECT_EQ(fprd(0x0130, 6).data, (std::vector<std::uint8_t>{0x12, 0x00, 0, 0, 0x11, 0x00}));
}

TEST_F(RegistersTest, AlControlWriteRaisesAlEventClearedByPdiRead) {
  EXPECT_EQ(esc->pdi_irq(), 0u);
  EXPECT_EQ(fpwr(0x0120, u16(0x0002)).wkc, 1);
  EXPECT_EQ(peek32(0x0220) & 0x01u, 0x01u);
  EXPECT_EQ(esc->pdi_irq() & 0x01u, 0x01u);
  pdi_write(0x0120, u16(0x0008));  // PDI cannot write AL control
  EXPECT_EQ(peek16(0x0120), 0x0002);
  EXPECT_EQ(pdi16(0x0120), 0x0002);
  EXPECT_EQ(peek32(0x0220) & 0x01u, 0u);
  EXPECT_EQ(esc->pdi_irq(), 0u);
}

TEST_F(RegistersTest, MasterReadingAlControlDoesNotClearTheEvent) {
  fpwr(0x0120, u16(0x0002));
  fprd(0x0120, 2);
  EXPECT_EQ(peek32(0x0220) & 0x01u, 0x01u);
}

TEST_F(RegistersTest, AlEventMaskWrittenByPdiGatesTheIrq) {
  fpwr(0x0204, {0, 0, 0, 0});  // ECAT may not write the AL event mask
  EXPECT_EQ(peek32(0x0204), 0x00FFFF0Fu);
  pdi_write(0x0204, {0x00, 0x00, 0x00, 0x00});
  fpwr(0x0120, u16(0x0002));
  EXPECT_EQ(peek32(0x0220) & 0x01u, 0x01u);
  EXPECT_EQ(esc->pdi_irq(), 0u);
  pdi_write(0x0204, {0x01, 0x00, 0x00, 0x00});
  EXPECT_EQ(esc->pdi_irq(), 0x01u);
}

TEST_F(RegistersTest, EventRequestRegistersAreReadOnly) {
  fpwr(0x0120, u16(0x0002));
  pdi_write(0x0220, {0, 0, 0, 0});
  fpwr(0x0220, {0, 0, 0, 0});
  EXPECT_EQ(peek32(0x0220) & 0x01u, 0x01u);
  pdi_write(0x0130, u16(0x0002));
  fpwr(0x0210, {0, 0});
  EXPECT_EQ(peek16(0x0210) & 0x0008, 0x0008);
}

TEST_F(RegistersTest, EcatEventMaskWrittenByEcatOnly) {
  pdi_write(0x0200, u16(0xFFFF));
  EXPECT_EQ(peek16(0x0200), 0);
  fpwr(0x0200, u16(0x0004));
  EXPECT_EQ(pdi16(0x0200), 0x0004);
}

TEST_F(RegistersTest, SyncManagerStatusAndPdiControlPermissions) {
  fpwr(0x0805, {0xFF});
  EXPECT_EQ(esc->peek(0x0805), 0);
  fpwr(0x0807, {0x01});
  EXPECT_EQ(esc->peek(0x0807), 0);
  pdi_write(0x0807, {0x02});
  EXPECT_EQ(fprd(0x0807, 1).data[0], 0x02);
  pdi_write(0x0800, {0x00, 0x18});  // PDI cannot configure an SM
  EXPECT_EQ(esc->peek(0x0801), 0);
}

TEST_F(RegistersTest, UnimplementedRegistersReadZeroAndIgnoreWrites) {
  EXPECT_EQ(fpwr(0x0E00, {1, 2, 3, 4}).wkc, 1);
  Result r = fprd(0x0E00, 4);
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{0, 0, 0, 0}));
  // FMMU 3 and SM 4 do not exist on a 3-FMMU / 4-SM ESC.
  fpwr(0x0630, {0xAA});
  fpwr(0x0820, {0xAA});
  EXPECT_EQ(esc->peek(0x0630), 0);
  EXPECT_EQ(esc->peek(0x0820), 0);
  fpwr(0x0620, {0xAA});
  EXPECT_EQ(esc->peek(0x0620), 0xAA);
}

TEST_F(RegistersTest, ProcessRamEndsAtConfiguredSize) {
  const std::uint16_t last = 0x1000 + 8 * 1024 - 1;
  EXPECT_EQ(fpwr(last, {0x5A, 0xA5}).wkc, 1);
  EXPECT_EQ(esc->peek(last), 0x5A);
  EXPECT_EQ(esc->peek(last + 1), 0);
  EXPECT_EQ(fprd(last, 2).data, (std::vector<std::uint8_t>{0x5A, 0x00}));
  pdi_write(0x4000, {0x77});
  EXPECT_EQ(pdi8(0x4000), 0);
}

TEST_F(RegistersTest, UserRamWritableByBothSides) {
  fpwr(0x0F80, {0x11});
  pdi_write(0x0FFF, {0x22});
  EXPECT_EQ(pdi8(0x0F80), 0x11);
  EXPECT_EQ(fprd(0x0FFF, 1).data[0], 0x22);
}

TEST_F(RegistersTest, DeviceEmulationCopiesAlControlToStatus) {
  VirtualClock c;
  EscConfig cfg;
  cfg.sii_image = sii_image(0, 0x0D05);  // 0x0141 bit0: device emulation
  Esc emu(cfg, c);
  ASSERT_EQ(emu.peek(0x0141) & 0x01, 0x01);
  Result r = send({&emu}, cmd::APWR, Frame::ap(0, 0x0120), u16(0x0002));
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(emu.peek(0x0130), 0x02);
  // Without emulation the status waits for the firmware.
  fpwr(0x0120, u16(0x0002));
  EXPECT_EQ(peek16(0x0130), 0x0001);
}

TEST_F(RegistersTest, DlStatusReflectsLinksAndLoopControl) {
  PortLinks links;
  links.port[0] = true;
  esc->set_links(links);
  std::uint16_t s = fprd(0x0110, 2).data[0] | (fprd(0x0110, 2).data[1] << 8);
  EXPECT_EQ(s & 0x00F0, 0x0010);        // link on port 0 only
  EXPECT_EQ((s >> 8) & 0x03, 0x02);     // port 0 open, communication established
  EXPECT_EQ((s >> 10) & 0x03, 0x01);    // port 1 closed (auto, no link)
  EXPECT_FALSE(esc->port_forwards(1));
  links.port[1] = true;
  esc->set_links(links);
  EXPECT_TRUE(esc->port_forwards(1));
  // Master closes port 1 manually (loop bits 10-11 = 11).
  fpwr(0x0101, {0x0C});
  EXPECT_FALSE(esc->port_forwards(1));
  EXPECT_EQ((peek16(0x0110) >> 10) & 0x03, 0x03);  // closed, but link/communication present
  fpwr(0x0101, {0x00});
  EXPECT_TRUE(esc->port_forwards(1));
}

TEST_F(RegistersTest, AutoCloseKeepsPortClosedAfterLinkLossUntilRewritten) {
  PortLinks links;
  links.port[0] = links.port[1] = true;
  esc->set_links(links);
  fpwr(0x0101, {0x04});  // port 1 auto close
  EXPECT_TRUE(esc->port_forwards(1));
  links.port[1] = false;
  esc->set_links(links);
  links.port[1] = true;
  esc->set_links(links);
  EXPECT_FALSE(esc->port_forwards(1));
  fpwr(0x0101, {0x04});
  EXPECT_TRUE(esc->port_forwards(1));
}

TEST_F(RegistersTest, LostLinkIsCountedPerPortAndClearedByMasterWrite) {
  PortLinks links;
  links.port[0] = links.port[1] = true;
  esc->set_links(links);
  for (int i = 0; i < 2; ++i) {
    links.port[1] = false;
    esc->set_links(links);
    links.port[1] = true;
    esc->set_links(links);
  }
  EXPECT_EQ(fprd(0x0310, 4).data, (std::vector<std::uint8_t>{0, 2, 0, 0}));
  fpwr(0x0310, {0});
  EXPECT_EQ(esc->peek(0x0311), 0);
}

TEST_F(RegistersTest, DlStatusChangeRaisesEcatEventClearedByReadingIt) {
  PortLinks links;
  links.port[0] = links.port[1] = true;
  esc->set_links(links);
  EXPECT_EQ(peek16(0x0210) & 0x0004, 0x0004);
  fprd(0x0110, 2);
  EXPECT_EQ(peek16(0x0210) & 0x0004, 0);
}

TEST_F(RegistersTest, MasterClosingPort0MarksFrameCirculatingAndSecondPassDestroysIt) {
  fpwr(0x0101, {0x03});  // port 0 loop: closed
  Frame f;
  f.add(cmd::BRD, Frame::ap(0, 0x0000), {0});
  EXPECT_TRUE(esc->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(f.len_field(0) & 0x4000, 0x4000);
  EXPECT_EQ(f.wkc(0), 1);
  EXPECT_FALSE(esc->process_frame(f.pdu(), FrameTiming{}));
  EXPECT_EQ(f.wkc(0), 1);  // destroyed, not processed again
}

TEST_F(RegistersTest, EscResetSequenceResetsTheChip) {
  fpwr(0x0F80, {0x99});
  fpwr(0x0040, {'R'});
  fpwr(0x0040, {'E'});
  EXPECT_EQ(peek16(0x0010), 0x1001);
  fpwr(0x0040, {'S'});
  EXPECT_EQ(peek16(0x0010), 0);
  EXPECT_EQ(esc->peek(0x0F80), 0);
  EXPECT_EQ(peek16(0x0012), 0x1234);  // EEPROM reloaded
}

TEST_F(RegistersTest, WrongResetSequenceDoesNothing) {
  fpwr(0x0040, {'R'});
  fpwr(0x0040, {'X'});
  fpwr(0x0040, {'S'});
  EXPECT_EQ(peek16(0x0010), 0x1001);
}

TEST_F(RegistersTest, ResetRestoresDefaults) {
  fpwr(0x0120, u16(0x0004));
  pdi_write(0x0204, {0, 0, 0, 0});
  esc->reset();
  EXPECT_EQ(peek16(0x0010), 0);
  EXPECT_EQ(peek16(0x0120), 0x0001);
  EXPECT_EQ(peek32(0x0204), 0x00FFFF0Fu);
  EXPECT_EQ(peek32(0x0220), 0u);
  EXPECT_EQ(peek16(0x0012), 0x1234);
}

TEST_F(RegistersTest, SmActivationChangeRaisesAlEventClearedByPdiReadingActivation) {
  fpwr(0x0800, sm_regs(0x1000, 128, 0x26));
  EXPECT_EQ(peek32(0x0220) & 0x10u, 0x10u);
  fprd(0x0806, 1);
  EXPECT_EQ(peek32(0x0220) & 0x10u, 0x10u);
  pdi8(0x0806);
  EXPECT_EQ(peek32(0x0220) & 0x10u, 0u);
}

}  // namespace
}  // namespace vdrive::esc::test
