// parse_sii() on a hand-built image laid out as ETG.1000.6 Table 16/19 describe it.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>
#include <vector>

#include "master/sii.hpp"

namespace vdrive::master {
namespace {

// Appends a category (type, bytes padded to whole words) to a word image.
void category(std::vector<std::uint16_t>& w, std::uint16_t type, std::vector<std::uint8_t> bytes) {
  if (bytes.size() % 2) bytes.push_back(0);
  w.push_back(type);
  w.push_back(static_cast<std::uint16_t>(bytes.size() / 2));
  for (std::size_t i = 0; i < bytes.size(); i += 2) w.push_back(static_cast<std::uint16_t>(bytes[i] | (bytes[i + 1] << 8)));
}

std::vector<std::uint8_t> strings(const std::vector<std::string>& s) {
  std::vector<std::uint8_t> b{static_cast<std::uint8_t>(s.size())};
  for (const auto& x : s) {
    b.push_back(static_cast<std::uint8_t>(x.size()));
    b.insert(b.end(), x.begin(), x.end());
  }
  return b;
}

std::vector<std::uint16_t> image() {
  std::vector<std::uint16_t> w(0x40, 0);
  w[0x04] = 0x0007;                       // alias
  w[0x08] = 0x066F; w[0x09] = 0x0000;     // vendor 0x0000066F
  w[0x0A] = 0x0003; w[0x0B] = 0x6010;     // product 0x60100003
  w[0x0C] = 0x0002; w[0x0D] = 0x0001;     // revision 0x00010002
  w[0x0E] = 0x5678; w[0x0F] = 0x1234;     // serial
  w[0x14] = 0x1000; w[0x15] = 0x0100; w[0x16] = 0x1100; w[0x17] = 0x0100;
  w[0x18] = 0x1800; w[0x19] = 0x0080; w[0x1A] = 0x1C00; w[0x1B] = 0x0080;
  w[0x1C] = 0x000C;                       // CoE + FoE
  w[0x3E] = 0x000F;                       // 16 kbit
  // General before Strings: the parser must resolve string indexes whatever the order.
  std::vector<std::uint8_t> general(32, 0);
  general[0] = 3;   // group
  general[2] = 2;   // order
  general[3] = 1;   // name
  general[5] = 0x2F;  // CoE details
  category(w, 30, general);
  category(w, 10, strings({"MINAS-A6B", "MADLN15BE", "Servo Drives", "Position"}));
  category(w, 40, {0x01, 0x02, 0x03});
  category(w, 41, {0x00, 0x18, 0x80, 0x00, 0x26, 0x00, 0x01, 0x01,
                   0x00, 0x1C, 0x80, 0x00, 0x22, 0x00, 0x01, 0x02});
  // TxPDO 0x1A00 on SM3 with one entry 0x6041:00, 16 bits, named by string 4.
  category(w, 50, {0x00, 0x1A, 0x01, 0x03, 0x00, 0x00, 0x00, 0x00,
                   0x41, 0x60, 0x00, 0x04, 0x06, 0x10, 0x00, 0x00});
  w.push_back(0xFFFF);
  w.push_back(0xFFFF);
  return w;
}

TEST(SiiParse, IdentityAndMailboxWords) {
  const SlaveInfo info = parse_sii(image());
  EXPECT_EQ(info.alias, 7);
  EXPECT_EQ(info.vendor_id, 0x0000066Fu);
  EXPECT_EQ(info.product_code, 0x60100003u);
  EXPECT_EQ(info.revision, 0x00010002u);
  EXPECT_EQ(info.serial, 0x12345678u);
  EXPECT_EQ(info.boot_rx_offset, 0x1000);
  EXPECT_EQ(info.boot_tx_size, 0x0100);
  EXPECT_EQ(info.mailbox_rx_offset, 0x1800);
  EXPECT_EQ(info.mailbox_rx_size, 0x80);
  EXPECT_EQ(info.mailbox_tx_offset, 0x1C00);
  EXPECT_EQ(info.mailbox_tx_size, 0x80);
  EXPECT_EQ(info.mailbox_protocols, mailbox_protocol::kCoE | mailbox_protocol::kFoE);
  EXPECT_EQ(info.eeprom_kbit, 16);
  EXPECT_TRUE(info.has_mailbox());
}

TEST(SiiParse, CategoriesStringsGeneralFmmuSmPdo) {
  const SlaveInfo info = parse_sii(image());
  ASSERT_EQ(info.strings.size(), 4u);
  EXPECT_EQ(info.name, "MINAS-A6B");
  EXPECT_EQ(info.order, "MADLN15BE");
  EXPECT_EQ(info.group, "Servo Drives");
  EXPECT_EQ(info.coe_details, 0x2F);
  EXPECT_EQ(info.fmmus, (std::vector<std::uint8_t>{1, 2, 3, 0}));  // the pad byte is read as "unused"
  ASSERT_EQ(info.sync_managers.size(), 2u);
  EXPECT_EQ(info.sync_managers[0].start, 0x1800);
  EXPECT_EQ(info.sync_managers[0].length, 0x80);
  EXPECT_EQ(info.sync_managers[0].control, 0x26);
  EXPECT_EQ(info.sync_managers[0].type, 1);
  EXPECT_EQ(info.sync_managers[1].control, 0x22);
  EXPECT_EQ(info.sync_managers[1].type, 2);
  ASSERT_EQ(info.tx_pdos.size(), 1u);
  EXPECT_EQ(info.tx_pdos[0].index, 0x1A00);
  EXPECT_EQ(info.tx_pdos[0].sync_manager, 3);
  ASSERT_EQ(info.tx_pdos[0].entries.size(), 1u);
  EXPECT_EQ(info.tx_pdos[0].entries[0].index, 0x6041);
  EXPECT_EQ(info.tx_pdos[0].entries[0].bit_length, 16);
  EXPECT_EQ(info.tx_pdos[0].entries[0].name, "Position");
}

TEST(SiiParse, TruncatedImagesAreReadOnlyAsFarAsTheyGo) {
  auto w = image();
  // A category claiming more words than the image holds, cut in the middle of the strings.
  w.resize(0x40 + 32 / 2 + 2 + 4);
  const SlaveInfo info = parse_sii(w);
  EXPECT_EQ(info.vendor_id, 0x0000066Fu);
  EXPECT_LE(info.strings.size(), 4u);
  // Too short even for the identity: zeros, no crash.
  const std::vector<std::uint16_t> tiny{0x1234};
  const SlaveInfo none = parse_sii(tiny);
  EXPECT_EQ(none.vendor_id, 0u);
  EXPECT_FALSE(none.has_mailbox());
}

TEST(SiiParse, StringIndexOutOfRangeGivesEmptyName) {
  std::vector<std::uint16_t> w(0x40, 0);
  std::vector<std::uint8_t> general(32, 0);
  general[3] = 9;  // no string 9
  category(w, 30, general);
  w.push_back(0xFFFF);
  const SlaveInfo info = parse_sii(w);
  EXPECT_TRUE(info.has_general);
  EXPECT_EQ(info.name, "");
}

// Whatever a slave's EEPROM holds, parsing stays inside the image (run under ASan in CI) and the
// result is bounded by it.
TEST(SiiParse, RandomImagesStayInBounds) {
  std::mt19937 rng(1234);
  for (int round = 0; round < 2000; ++round) {
    std::vector<std::uint16_t> w(std::uniform_int_distribution<std::size_t>(0, 0x200)(rng));
    for (auto& x : w) x = static_cast<std::uint16_t>(rng());
    // Half the images get plausible category headers so the category parsers run too.
    if (round % 2 && w.size() > 0x44) {
      w[0x40] = static_cast<std::uint16_t>(std::array<int, 6>{10, 30, 40, 41, 50, 51}[rng() % 6]);
      w[0x41] = static_cast<std::uint16_t>(rng() % 0x300);
    }
    const SlaveInfo info = parse_sii(w);
    EXPECT_LE(info.strings.size(), 255u);
    EXPECT_LE(info.sync_managers.size() * 4, w.size());
    EXPECT_LE(info.fmmus.size(), 2 * w.size());
  }
}

}  // namespace
}  // namespace vdrive::master
