// PDO configuration over CoE (read and remap, the CiA 301 way: subindex 0 to 0, entries, count)
// against the stand-in mailbox firmware on a bare ESC, and from the SII PDO categories.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "master/master.hpp"
#include "master/process_data.hpp"
#include "master/registers.hpp"
#include "tests/master/bare_esc_link.hpp"
#include "tests/master/coe_test_server.hpp"

namespace vdrive::master {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes u16(std::uint16_t v) { return {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)}; }
Bytes u32(std::uint32_t v) {
  return {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v >> 16),
          static_cast<std::uint8_t>(v >> 24)};
}

class PdoConfig : public ::testing::Test {
protected:
  test::BareEscLink line{"a6b"};
  Master master{line, line.clock()};
  test::CoeTestServer server{line.esc()};

  void SetUp() override {
    ASSERT_EQ(master.scan(), 1u);
    for (std::size_t n = 0; n < 2; ++n) {
      const SmSetting& sm = master.slaves()[0].mailbox_sm[n];
      const std::array<std::uint8_t, 8> regs{static_cast<std::uint8_t>(sm.start), static_cast<std::uint8_t>(sm.start >> 8),
                                             static_cast<std::uint8_t>(sm.length), static_cast<std::uint8_t>(sm.length >> 8),
                                             sm.control, 0, sm.activate, 0};
      ASSERT_EQ(master.transport().fpwr(0x1001, static_cast<std::uint16_t>(reg::kSm0 + 8 * n), regs), 1);
    }
    master.set_mailbox_timeout(50'000'000);
    line.after_frame = [this] { server.service(); };
    auto& d = server.dictionary;
    d[0x1C12].entries = {{0, {{1}, true, ""}}, {1, {u16(0x1600), true, ""}}, {2, {u16(0), true, ""}}};
    d[0x1C13].entries = {{0, {{1}, true, ""}}, {1, {u16(0x1A00), true, ""}}, {2, {u16(0), true, ""}}};
    d[0x1600].entries = {{0, {{2}, true, ""}}, {1, {u32(0x60400010), true, ""}}, {2, {u32(0x607A0020), true, ""}},
                         {3, {u32(0), true, ""}}};
    d[0x1601].entries = {{0, {{0}, true, ""}}, {1, {u32(0), true, ""}}, {2, {u32(0), true, ""}}};
    d[0x1A00].entries = {{0, {{3}, true, ""}}, {1, {u32(0x60410010), true, ""}}, {2, {u32(0x60640020), true, ""}},
                         {3, {u32(0x60610008), true, ""}}};
  }
};

TEST_F(PdoConfig, ReadsAssignmentAndMappingOverCoe) {
  SlaveProcessData pd;
  read_pdo_configuration(master.sdo(0), pd);
  EXPECT_TRUE(pd.from_coe);
  ASSERT_EQ(pd.outputs.size(), 1u);
  EXPECT_EQ(pd.outputs[0].pdo, 0x1600);
  EXPECT_EQ(pd.outputs[0].entries, (std::vector<std::uint32_t>{0x60400010, 0x607A0020}));
  EXPECT_EQ(pd.outputs[0].bits(), 48u);
  ASSERT_EQ(pd.inputs.size(), 1u);
  EXPECT_EQ(pd.inputs[0].bits(), 56u);
}

TEST_F(PdoConfig, RemapsAPdoAndTheAssignment) {
  SdoClient& sdo = master.sdo(0);
  const std::array<std::uint32_t, 2> entries{0x60600008, 0x60FF0020};
  map_pdo(sdo, 0x1601, entries);
  const std::array<std::uint16_t, 2> pdos{0x1600, 0x1601};
  assign_pdos(sdo, 0x1C12, pdos);
  EXPECT_EQ(server.dictionary[0x1601].entries[0].value, Bytes{2});
  EXPECT_EQ(server.dictionary[0x1601].entries[2].value, u32(0x60FF0020));
  EXPECT_EQ(server.dictionary[0x1C12].entries[0].value, Bytes{2});
  EXPECT_EQ(server.dictionary[0x1C12].entries[2].value, u16(0x1601));
  SlaveProcessData pd;
  read_pdo_configuration(sdo, pd);
  ASSERT_EQ(pd.outputs.size(), 2u);
  EXPECT_EQ(pd.outputs[0].bits() + pd.outputs[1].bits(), 48u + 40u);
}

TEST_F(PdoConfig, RefusedRemapSurfacesTheAbort) {
  server.dictionary[0x1601].entries[1].writable = false;  // a fixed mapping
  const std::array<std::uint32_t, 1> entries{0x60600008};
  try {
    map_pdo(master.sdo(0), 0x1601, entries);
    FAIL() << "no abort";
  } catch (const SdoAbort& e) {
    EXPECT_EQ(e.code(), 0x06010002u);
    EXPECT_EQ(e.index(), 0x1601);
    EXPECT_EQ(e.subindex(), 1);
  }
}

TEST(SiiPdoConfig, TakesRxPdosOfSm2AndTxPdosOfSm3) {
  SlaveInfo info;
  info.rx_pdos.push_back(SiiPdo{0x1600, 2, "out", {{0x6040, 0, 6, 16, ""}, {0x607A, 0, 4, 32, ""}}});
  info.rx_pdos.push_back(SiiPdo{0x1601, 0, "unassigned", {{0x6060, 0, 2, 8, ""}}});
  info.tx_pdos.push_back(SiiPdo{0x1A00, 3, "in", {{0x6041, 0, 6, 16, ""}}});
  SlaveProcessData pd;
  sii_pdo_configuration(info, pd);
  EXPECT_FALSE(pd.from_coe);
  ASSERT_EQ(pd.outputs.size(), 1u) << "a PDO with SM 0 is not assigned";
  EXPECT_EQ(pd.outputs[0].entries, (std::vector<std::uint32_t>{0x60400010, 0x607A0020}));
  ASSERT_EQ(pd.inputs.size(), 1u);
  EXPECT_EQ(pd.inputs[0].bits(), 16u);
}

}  // namespace
}  // namespace vdrive::master
