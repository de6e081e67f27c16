// SyncManagers: mailbox full/empty handshake, working counter, events, repeat; 3-buffer
// rotation and reader locking; configuration lock while enabled.
#include <gtest/gtest.h>

#include <numeric>

#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

// Control bytes: mode bits 0-1 (00 buffered, 10 mailbox), direction 2-3 (01 = ECAT writes),
// bit 4 ECAT event, bit 5 AL event, bit 6 watchdog trigger.
constexpr std::uint8_t kMailboxEcatWrites = 0x26;
constexpr std::uint8_t kMailboxEcatReads = 0x22;
constexpr std::uint8_t kBufferedEcatWrites = 0x64;
constexpr std::uint8_t kBufferedEcatReads = 0x20;

constexpr std::uint16_t kMbxOut = 0x1000;  // SM0
constexpr std::uint16_t kMbxIn = 0x1080;   // SM1
constexpr std::uint16_t kMbxLen = 16;

std::vector<std::uint8_t> pattern(std::size_t n, std::uint8_t first) {
  std::vector<std::uint8_t> v(n);
  std::iota(v.begin(), v.end(), first);
  return v;
}

class SyncManagerTest : public EscTest {
protected:
  void SetUp() override {
    set_station();
    ASSERT_EQ(fpwr(0x0800, sm_regs(kMbxOut, kMbxLen, kMailboxEcatWrites)).wkc, 1);
    ASSERT_EQ(fpwr(0x0808, sm_regs(kMbxIn, kMbxLen, kMailboxEcatReads)).wkc, 1);
    pdi8(0x0806);  // acknowledge "SM activation changed"
  }
  std::vector<std::uint8_t> pdi_read(std::uint16_t a, std::size_t n) {
    std::vector<std::uint8_t> v(n);
    esc->pdi_read(a, v);
    return v;
  }
  std::uint8_t status(int sm) { return esc->peek(static_cast<std::uint16_t>(0x0805 + 8 * sm)); }
};

TEST_F(SyncManagerTest, WriteMailboxFullAfterLastByteAndRejectsFurtherWrites) {
  Result first = fpwr(kMbxOut, pattern(kMbxLen, 1));
  EXPECT_EQ(first.wkc, 1);
  EXPECT_EQ(status(0) & 0x08, 0x08);   // full
  EXPECT_EQ(status(0) & 0x01, 0x01);   // IRQ write
  EXPECT_EQ(esc->pdi_irq() & 0x100u, 0x100u);  // AL event SM0
  Result second = fpwr(kMbxOut, pattern(kMbxLen, 100));
  EXPECT_EQ(second.wkc, 0);
  EXPECT_EQ(esc->peek(kMbxOut), 1);  // first message kept
}

TEST_F(SyncManagerTest, WriteMailboxNotFullUntilLastByteWritten) {
  EXPECT_EQ(fpwr(kMbxOut, pattern(kMbxLen - 1, 1)).wkc, 1);
  EXPECT_EQ(status(0) & 0x08, 0);
  EXPECT_EQ(status(0) & 0x80, 0x80);  // write buffer open
  EXPECT_EQ(esc->pdi_irq() & 0x100u, 0u);
  EXPECT_EQ(fpwr(kMbxOut + kMbxLen - 1, {0xEE}).wkc, 1);
  EXPECT_EQ(status(0) & 0x08, 0x08);
}

TEST_F(SyncManagerTest, PdiReadingWriteMailboxEmptiesItAndClearsEvent) {
  fpwr(kMbxOut, pattern(kMbxLen, 1));
  EXPECT_EQ(pdi_read(kMbxOut, 1)[0], 1);  // first byte: IRQ write cleared
  EXPECT_EQ(esc->pdi_irq() & 0x100u, 0u);
  EXPECT_EQ(status(0) & 0x08, 0x08);      // still full until the last byte
  EXPECT_EQ(pdi_read(kMbxOut + 1, kMbxLen - 1), pattern(kMbxLen - 1, 2));
  EXPECT_EQ(status(0) & 0x08, 0);
  EXPECT_EQ(status(0) & 0x02, 0x02);  // IRQ read (signalled to the master)
  EXPECT_EQ(fpwr(kMbxOut, pattern(kMbxLen, 50)).wkc, 1);
  EXPECT_EQ(status(0) & 0x02, 0);
}

TEST_F(SyncManagerTest, ReadingEmptyReadMailboxReturnsNoDataAndNoWkc) {
  Result r = fprd(kMbxIn, kMbxLen);
  EXPECT_EQ(r.wkc, 0);
  EXPECT_EQ(r.data, std::vector<std::uint8_t>(kMbxLen, 0));
  // Data already in the datagram stays as it was.
  Result kept = send({esc.get()}, cmd::FPRD, Frame::ap(0x1001, kMbxIn),
                     std::vector<std::uint8_t>(4, 0xAA));
  EXPECT_EQ(kept.data, std::vector<std::uint8_t>(4, 0xAA));
}

TEST_F(SyncManagerTest, ReadMailboxHandshake) {
  pdi_write(kMbxIn, pattern(kMbxLen, 10));
  EXPECT_EQ(status(1) & 0x08, 0x08);
  Result r = fprd(kMbxIn, kMbxLen);
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(r.data, pattern(kMbxLen, 10));
  EXPECT_EQ(status(1) & 0x08, 0);
  EXPECT_EQ(esc->pdi_irq() & 0x200u, 0x200u);  // buffer read: the PDI may write again
  EXPECT_EQ(fprd(kMbxIn, kMbxLen).wkc, 0);
  pdi_write(kMbxIn, pattern(kMbxLen, 20));
  EXPECT_EQ(esc->pdi_irq() & 0x200u, 0u);  // cleared by writing the first byte
  EXPECT_EQ(fprd(kMbxIn, kMbxLen).data, pattern(kMbxLen, 20));
}

TEST_F(SyncManagerTest, PdiCannotOverwriteFullReadMailbox) {
  pdi_write(kMbxIn, pattern(kMbxLen, 10));
  pdi_write(kMbxIn, pattern(kMbxLen, 90));
  EXPECT_EQ(fprd(kMbxIn, kMbxLen).data, pattern(kMbxLen, 10));
}

TEST_F(SyncManagerTest, MasterCannotWriteReadMailbox) {
  EXPECT_EQ(fpwr(kMbxIn, pattern(kMbxLen, 1)).wkc, 0);
  EXPECT_EQ(esc->peek(kMbxIn), 0);
}

TEST_F(SyncManagerTest, EcatEventForReadMailboxReachesTheMasterThroughIrqField) {
  fpwr(0x0806 + 8, {0x00});
  fpwr(0x0808, sm_regs(kMbxIn, kMbxLen, kMailboxEcatReads | 0x10));
  fpwr(0x0200, u16(0x0020));  // ECAT event mask: SM1
  pdi_write(kMbxIn, pattern(kMbxLen, 1));
  EXPECT_EQ(peek16(0x0210) & 0x0020, 0x0020);
  Frame f;
  f.add(cmd::NOP, 0, {0});
  esc->process_frame(f.pdu(), FrameTiming{});
  EXPECT_EQ(f.irq(0), 0x0020);
  fprd(kMbxIn, kMbxLen);
  EXPECT_EQ(peek16(0x0210) & 0x0020, 0);
}

TEST_F(SyncManagerTest, RepeatRequestAndAcknowledge) {
  fpwr(0x080E, {0x03});  // SM1 enable + toggle repeat request
  EXPECT_EQ(peek32(0x0220) & 0x10u, 0x10u);  // SM activation changed
  EXPECT_EQ(pdi8(0x080E) & 0x02, 0x02);
  EXPECT_EQ(peek32(0x0220) & 0x10u, 0u);
  EXPECT_TRUE(esc->peek(0x0808 + 5) == status(1));
  pdi_write(0x080F, {0x02});  // repeat acknowledge
  EXPECT_EQ(fprd(0x080F, 1).data[0] & 0x02, 0x02);
  // The SM stayed enabled through the toggle.
  pdi_write(kMbxIn, pattern(kMbxLen, 1));
  EXPECT_EQ(fprd(kMbxIn, kMbxLen).wkc, 1);
}

TEST_F(SyncManagerTest, ConfigurationLockedWhileEnabled) {
  fpwr(0x0800, u16(0x1400));
  EXPECT_EQ(peek16(0x0800), kMbxOut);
  fpwr(0x0806, {0x00});
  fpwr(0x0800, u16(0x1400));
  EXPECT_EQ(peek16(0x0800), 0x1400);
}

TEST_F(SyncManagerTest, DisablingResetsMailboxState) {
  fpwr(kMbxOut, pattern(kMbxLen, 1));
  fpwr(0x0806, {0x00});
  EXPECT_EQ(status(0), 0);
  EXPECT_EQ(esc->pdi_irq() & 0x100u, 0u);
  fpwr(0x0806, {0x01});
  EXPECT_EQ(fpwr(kMbxOut, pattern(kMbxLen, 1)).wkc, 1);
}

TEST_F(SyncManagerTest, PdiDeactivateDisablesTheSm) {
  fpwr(kMbxOut, pattern(kMbxLen, 1));
  pdi_write(0x0807, {0x01});
  EXPECT_EQ(status(0), 0);
  // Disabled SM: the area is plain memory again.
  EXPECT_EQ(fpwr(kMbxOut, {0x77}).wkc, 1);
  EXPECT_EQ(esc->peek(kMbxOut), 0x77);
  pdi_write(0x0807, {0x00});
  EXPECT_EQ(status(0) & 0x08, 0);
}

// ---- 3-buffer mode ---------------------------------------------------------------------------

constexpr std::uint16_t kOut = 0x1100;  // SM2: ECAT writes, 4 bytes (occupies 0x1100-0x110B)
constexpr std::uint16_t kIn = 0x1180;   // SM3: ECAT reads
constexpr std::uint16_t kLen = 4;

class BufferedTest : public SyncManagerTest {
protected:
  void SetUp() override {
    SyncManagerTest::SetUp();
    ASSERT_EQ(fpwr(0x0810, sm_regs(kOut, kLen, kBufferedEcatWrites)).wkc, 1);
    ASSERT_EQ(fpwr(0x0818, sm_regs(kIn, kLen, kBufferedEcatReads)).wkc, 1);
  }
};

TEST_F(BufferedTest, NothingWrittenYet) {
  EXPECT_EQ((status(2) >> 4) & 0x03, 0x03);
  Result r = fprd(kIn, kLen);
  EXPECT_EQ(r.wkc, 1);  // 3-buffer mode never blocks
  EXPECT_EQ(r.data, std::vector<std::uint8_t>(kLen, 0));
}

TEST_F(BufferedTest, WritesRotateBuffersAndReaderGetsNewest) {
  EXPECT_EQ(fpwr(kOut, {1, 2, 3, 4}).wkc, 1);
  EXPECT_EQ((status(2) >> 4) & 0x03, 0);
  EXPECT_EQ(esc->pdi_irq() & 0x400u, 0x400u);
  EXPECT_EQ(fpwr(kOut, {5, 6, 7, 8}).wkc, 1);
  EXPECT_EQ((status(2) >> 4) & 0x03, 1);
  EXPECT_EQ(esc->peek(kOut + kLen), 5);  // second buffer in physical memory
  EXPECT_EQ(pdi_read(kOut, kLen), (std::vector<std::uint8_t>{5, 6, 7, 8}));
  EXPECT_EQ(esc->pdi_irq() & 0x400u, 0u);
  // Writes never block, even back to back with no reader.
  for (int i = 0; i < 5; ++i) EXPECT_EQ(fpwr(kOut, {9, 9, 9, static_cast<std::uint8_t>(i)}).wkc, 1);
  EXPECT_EQ(pdi_read(kOut, kLen), (std::vector<std::uint8_t>{9, 9, 9, 4}));
}

TEST_F(BufferedTest, ReaderKeepsItsBufferWhileWriterContinues) {
  fpwr(kOut, {1, 2, 3, 4});
  EXPECT_EQ(pdi_read(kOut, 1)[0], 1);  // opens and locks buffer 0
  EXPECT_EQ(status(2) & 0x40, 0x40);    // read buffer open
  fpwr(kOut, {5, 6, 7, 8});
  fpwr(kOut, {9, 10, 11, 12});
  fpwr(kOut, {13, 14, 15, 16});
  EXPECT_EQ(pdi_read(kOut + 1, 3), (std::vector<std::uint8_t>{2, 3, 4}));
  EXPECT_EQ(status(2) & 0x40, 0);
  EXPECT_EQ(pdi_read(kOut, kLen), (std::vector<std::uint8_t>{13, 14, 15, 16}));
}

TEST_F(BufferedTest, RereadWithoutNewDataGivesSameData) {
  fpwr(kOut, {1, 2, 3, 4});
  EXPECT_EQ(pdi_read(kOut, kLen), (std::vector<std::uint8_t>{1, 2, 3, 4}));
  EXPECT_EQ(pdi_read(kOut, kLen), (std::vector<std::uint8_t>{1, 2, 3, 4}));
}

TEST_F(BufferedTest, IncompleteWriteDoesNotBecomeNewest) {
  fpwr(kOut, {1, 2, 3, 4});
  fpwr(kOut, {7, 7});  // master wrote only half the buffer
  EXPECT_EQ(status(2) & 0x80, 0x80);
  EXPECT_EQ(pdi_read(kOut, kLen), (std::vector<std::uint8_t>{1, 2, 3, 4}));
}

TEST_F(BufferedTest, InputsWrittenByPdiReadByMaster) {
  pdi_write(kIn, {0xA1, 0xA2, 0xA3, 0xA4});
  pdi_write(kIn, {0xB1, 0xB2, 0xB3, 0xB4});
  Result r = fprd(kIn, kLen);
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{0xB1, 0xB2, 0xB3, 0xB4}));
  EXPECT_EQ(fpwr(kIn, {0, 0, 0, 0}).wkc, 0);  // the master cannot write an input buffer
}

}  // namespace
}  // namespace vdrive::esc::test

namespace vdrive::esc::test {
namespace {

// A digital output terminal's SM0 on the digital output data (0x0F00, one byte, 3-buffered,
// ECAT writes, no AL event as on an EL2008): the master's writes go through the SyncManager and
// the PDI reads the latest complete buffer.
class DigitalOutputSm : public EscTest {};

TEST_F(DigitalOutputSm, WritesToTheOutputRegisterGoThroughItsSyncManager) {
  set_station();
  ASSERT_EQ(fpwr(0x0800, {0x00, 0x0F, 0x01, 0x00, 0x44, 0x00, 0x01, 0x00}).wkc, 1);  // SM0: 0F00h, 1 byte, 3-buffer, write
  pdi8(0x0806);
  EXPECT_EQ(pdi8(0x0F00), 0x00) << "nothing written yet";
  EXPECT_EQ(fpwr(0x0F00, {0xA5}).wkc, 1);
  EXPECT_EQ(pdi8(0x0F00), 0xA5) << "the PDI reads the buffer the master completed";
  EXPECT_EQ(fpwr(0x0F00, {0x5A}).wkc, 1);
  EXPECT_EQ(fpwr(0x0F00, {0x3C}).wkc, 1);
  EXPECT_EQ(pdi8(0x0F00), 0x3C) << "3-buffered: the newest complete buffer";
}

}  // namespace
}  // namespace vdrive::esc::test
