// Logical addressing through FMMUs: byte and bit mappings, per-direction working counters.
#include <gtest/gtest.h>

#include "esc_model/fmmu.hpp"
#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

// FMMU register block: logical start, length, start bit, stop bit, physical start, physical
// start bit, type, activate.
std::vector<std::uint8_t> fmmu_regs(std::uint32_t logical, std::uint16_t len, std::uint16_t phys,
                                    std::uint8_t type, std::uint8_t start_bit = 0,
                                    std::uint8_t stop_bit = 7, std::uint8_t phys_bit = 0,
                                    std::uint8_t activate = 1) {
  return {static_cast<std::uint8_t>(logical), static_cast<std::uint8_t>(logical >> 8),
          static_cast<std::uint8_t>(logical >> 16), static_cast<std::uint8_t>(logical >> 24),
          static_cast<std::uint8_t>(len), static_cast<std::uint8_t>(len >> 8), start_bit,
          stop_bit, static_cast<std::uint8_t>(phys), static_cast<std::uint8_t>(phys >> 8),
          phys_bit, type, activate, 0, 0, 0};
}

constexpr std::uint8_t kRead = 1;
constexpr std::uint8_t kWrite = 2;

class FmmuTest : public EscTest {
protected:
  void SetUp() override {
    set_station();
    // Outputs: logical 0x10000..0x10003 -> 0x1100; inputs: 0x10004..0x10005 -> 0x1200.
    ASSERT_EQ(fpwr(0x0600, fmmu_regs(0x10000, 4, 0x1100, kWrite)).wkc, 1);
    ASSERT_EQ(fpwr(0x0610, fmmu_regs(0x10004, 2, 0x1200, kRead)).wkc, 1);
    pdi_write(0x1200, {0xC1, 0xC2});
  }
  Result logical(std::uint8_t command, std::uint32_t address, std::vector<std::uint8_t> data) {
    return send({esc.get()}, command, address, std::move(data));
  }
};

TEST_F(FmmuTest, LwrWritesThroughWriteFmmuOnly) {
  Result r = logical(cmd::LWR, 0x10000, {1, 2, 3, 4, 5, 6});
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(esc->peek(0x1100), 1);
  EXPECT_EQ(esc->peek(0x1103), 4);
  EXPECT_EQ(esc->peek(0x1200), 0xC1);  // the read FMMU does not write
}

TEST_F(FmmuTest, LrdReadsThroughReadFmmuOnlyAndLeavesOtherBytes) {
  Result r = logical(cmd::LRD, 0x10000, {9, 9, 9, 9, 9, 9, 9});
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{9, 9, 9, 9, 0xC1, 0xC2, 9}));
}

TEST_F(FmmuTest, LrwCountsReadOneWriteTwo) {
  Result both = logical(cmd::LRW, 0x10000, {1, 2, 3, 4, 0, 0});
  EXPECT_EQ(both.wkc, 3);
  EXPECT_EQ(both.data[4], 0xC1);
  EXPECT_EQ(esc->peek(0x1102), 3);
  EXPECT_EQ(logical(cmd::LRW, 0x10000, {1, 2, 3, 4}).wkc, 2);   // write window only
  EXPECT_EQ(logical(cmd::LRW, 0x10004, {0, 0}).wkc, 1);         // read window only
}

TEST_F(FmmuTest, NoMatchingWindowLeavesWkcAndData) {
  Result r = logical(cmd::LRD, 0x20000, {7, 7});
  EXPECT_EQ(r.wkc, 0);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{7, 7}));
  EXPECT_EQ(logical(cmd::LWR, 0x0FFFC, {1, 2, 3, 4}).wkc, 0);
}

TEST_F(FmmuTest, PartialOverlapMapsOnlyTheOverlap) {
  Result r = logical(cmd::LWR, 0x0FFFE, {0xA, 0xB, 0xC, 0xD});
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(esc->peek(0x1100), 0xC);
  EXPECT_EQ(esc->peek(0x1101), 0xD);
  EXPECT_EQ(esc->peek(0x1102), 0);
}

TEST_F(FmmuTest, InactiveFmmuDoesNotMap) {
  fpwr(0x060C, {0});
  EXPECT_EQ(logical(cmd::LWR, 0x10000, {1, 2, 3, 4}).wkc, 0);
  EXPECT_EQ(esc->peek(0x1100), 0);
}

TEST_F(FmmuTest, LrwOverOverlappingReadAndWriteWindowsWritesWhatTheMasterSent) {
  // Inputs mapped onto the same logical bytes as the outputs (overlapping process image).
  fpwr(0x0610, fmmu_regs(0x10000, 2, 0x1200, kRead));
  Result r = logical(cmd::LRW, 0x10000, {0x11, 0x22, 0x33, 0x44});
  EXPECT_EQ(r.wkc, 3);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{0xC1, 0xC2, 0x33, 0x44}));
  EXPECT_EQ(esc->peek(0x1100), 0x11);
  EXPECT_EQ(esc->peek(0x1101), 0x22);
}

TEST_F(FmmuTest, LrwDeepInALongImageWritesWhatTheMasterSentWhereAnEarlierReadWindowOverlaps) {
  // FMMU 0 reads 0x10002..0x10005 back before FMMU 1 writes 0x10000..0x10003 and FMMU 2 bits
  // 2..5 of 0x10005: the writes must still store the master's bits. The windows sit 1,000 bytes
  // into a 1,400-byte datagram.
  fpwr(0x0600, fmmu_regs(0x10002, 4, 0x1200, kRead));
  fpwr(0x0610, fmmu_regs(0x10000, 4, 0x1100, kWrite));
  fpwr(0x0620, fmmu_regs(0x10005, 1, 0x1300, kWrite, 2, 5, 2));
  pdi_write(0x1202, {0x00, 0x00});
  constexpr std::uint32_t kStart = 0x10000 - 1000;
  std::vector<std::uint8_t> image(1400, 0xEE);
  image[1000] = 0x11;
  image[1001] = 0x22;
  image[1002] = 0x33;
  image[1003] = 0x44;
  image[1005] = 0x3C;  // bits 2..5 set
  Result r = logical(cmd::LRW, kStart, image);
  EXPECT_EQ(r.wkc, 3);
  EXPECT_EQ(r.data[1002], 0xC1);
  EXPECT_EQ(r.data[1003], 0xC2);
  EXPECT_EQ(r.data[1005], 0x00) << "read back from 0x1203";
  EXPECT_EQ(r.data[999], 0xEE) << "bytes of other slaves pass untouched";
  EXPECT_EQ(esc->peek(0x1100), 0x11);
  EXPECT_EQ(esc->peek(0x1101), 0x22);
  EXPECT_EQ(esc->peek(0x1102), 0x33);
  EXPECT_EQ(esc->peek(0x1103), 0x44);
  EXPECT_EQ(esc->peek(0x1300), 0x3C);
}

TEST_F(FmmuTest, LrwThroughTwoSlavesAccumulatesWorkingCounter) {
  VirtualClock c2;
  Esc second(default_config(), c2);
  send({&second}, cmd::APWR, Frame::ap(0, 0x0610), fmmu_regs(0x10006, 2, 0x1000, kRead));
  second.pdi_write(0x1000, std::vector<std::uint8_t>{0xD1, 0xD2});
  Result r = send({esc.get(), &second}, cmd::LRW, 0x10000, {1, 2, 3, 4, 0, 0, 0, 0});
  EXPECT_EQ(r.wkc, 4);  // slave 1: read + write, slave 2: read
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{1, 2, 3, 4, 0xC1, 0xC2, 0xD1, 0xD2}));
}

TEST_F(FmmuTest, SingleBitOfSm1StatusMapsIntoALogicalBit) {
  // SM1: read mailbox 0x1C00 (8 bytes, ECAT reads); its status 0x080D bit 3 = mailbox full.
  fpwr(0x0808, sm_regs(0x1C00, 8, 0x02));
  // FMMU 2: logical 0x30000 bit 5 <- physical 0x080D bit 3.
  fpwr(0x0620, fmmu_regs(0x30000, 1, 0x080D, kRead, 5, 5, 3));
  Result empty = logical(cmd::LRD, 0x30000, {0xFF});
  EXPECT_EQ(empty.wkc, 1);
  EXPECT_EQ(empty.data[0], 0xDF);  // only bit 5 is replaced
  pdi_write(0x1C00, std::vector<std::uint8_t>(8, 0x5A));
  ASSERT_EQ(esc->peek(0x080D) & 0x08, 0x08);
  Result full = logical(cmd::LRD, 0x30000, {0x00});
  EXPECT_EQ(full.data[0], 0x20);
  // Reading the status bit does not touch the mailbox.
  EXPECT_EQ(esc->peek(0x080D) & 0x08, 0x08);
}

TEST_F(FmmuTest, BitWindowAcrossByteBoundaryWritesOnlyMappedBits) {
  // Logical 0x40000 bit 4 .. 0x40001 bit 1 (6 bits) -> physical 0x1300 bits 2..7.
  fpwr(0x0620, fmmu_regs(0x40000, 2, 0x1300, kWrite, 4, 1, 2));
  pdi_write(0x1300, {0x03, 0xFF});
  Result r = logical(cmd::LWR, 0x40000, {0xA0, 0x03});
  EXPECT_EQ(r.wkc, 1);
  // Logical bits 4..9 = 0,1,0,1,1,1 -> physical bits 2..7; bits 0-1 and byte 0x1301 keep theirs.
  EXPECT_EQ(esc->peek(0x1300), 0xEB);
  EXPECT_EQ(esc->peek(0x1301), 0xFF);
}

TEST_F(FmmuTest, EmptyReadMailboxThroughFmmuDoesNotCount) {
  fpwr(0x0808, sm_regs(0x1C00, 4, 0x02));
  fpwr(0x0620, fmmu_regs(0x50000, 4, 0x1C00, kRead));
  Result r = logical(cmd::LRD, 0x50000, {1, 1, 1, 1});
  EXPECT_EQ(r.wkc, 0);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{1, 1, 1, 1}));
}

TEST(FmmuDecode, DecodesRegisterBlock) {
  const std::vector<std::uint8_t> raw = fmmu_regs(0x12345678, 0x0102, 0x1A00, 3, 2, 6, 5);
  const Fmmu f = Fmmu::decode(std::span<const std::uint8_t, 16>(raw.data(), 16));
  EXPECT_EQ(f.logical_start, 0x12345678u);
  EXPECT_EQ(f.length, 0x0102);
  EXPECT_EQ(f.logical_start_bit, 2);
  EXPECT_EQ(f.logical_stop_bit, 6);
  EXPECT_EQ(f.physical_start, 0x1A00);
  EXPECT_EQ(f.physical_start_bit, 5);
  EXPECT_TRUE(f.readable);
  EXPECT_TRUE(f.writable);
  EXPECT_TRUE(f.active);
}

}  // namespace
}  // namespace vdrive::esc::test
