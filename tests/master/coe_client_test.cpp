// The CoE client (mailbox + SDO + SDO info) against a real ESC's SyncManagers in virtual time,
// with a specification-based stand-in for the slave's mailbox firmware (coe_test_server.hpp).
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "master/coe.hpp"
#include "master/master.hpp"
#include "tests/master/coe_test_server.hpp"
#include "master/registers.hpp"
#include "tests/master/bare_esc_link.hpp"

namespace vdrive::master {
namespace {

using Bytes = std::vector<std::uint8_t>;

class CoeClient : public ::testing::Test {
protected:
  test::BareEscLink line{"a6b"};
  Master master{line, line.clock()};
  test::CoeTestServer server{line.esc()};

  void SetUp() override {
    ASSERT_EQ(master.scan(), 1u);
    // No firmware behind this ESC: enable the mailbox SMs as a master does before Pre-Op.
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
    d[0x1000].entries[0] = {{0x92, 0x01, 0x02, 0x00}, false, "Device type"};
    d[0x6040].entries[0] = {{0x00, 0x00}, true, "Controlword"};
    d[0x6060].entries[0] = {{0x08}, true, "Modes of operation"};
    d[0x1008].entries[0] = {Bytes{'M', 'A', 'D', 'L', 'N', '1', '5', 'B', 'E'}, false, "Device name"};
    d[0x1C32] = {"SM output parameter", 9, {}};
    d[0x1C32].entries[0] = {{2}, false, "Number"};
    d[0x1C32].entries[1] = {{0x02, 0x00}, true, "Sync mode"};
    d[0x1C32].entries[2] = {{0x40, 0x42, 0x0F, 0x00}, true, "Cycle time"};
    d[0x1C32].name = "SM output parameter";
  }
  SdoClient& sdo() { return master.sdo(0); }
  static Bytes pattern(std::size_t n) {
    Bytes b(n);
    for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::uint8_t>(i * 7 + 3);
    return b;
  }
};

TEST_F(CoeClient, ExpeditedUploadOfEachSize) {
  EXPECT_EQ(sdo().upload(0x6060, 0), (Bytes{0x08}));
  EXPECT_EQ(sdo().upload(0x6040, 0), (Bytes{0x00, 0x00}));
  EXPECT_EQ(sdo().upload_value<std::uint32_t>(0x1000, 0), 0x00020192u);
}

TEST_F(CoeClient, ExpeditedDownloadIsStored) {
  sdo().download_value<std::uint16_t>(0x6040, 0, 0x000F);
  EXPECT_EQ(server.dictionary[0x6040].entries[0].value, (Bytes{0x0F, 0x00}));
  EXPECT_EQ(sdo().upload_value<std::uint16_t>(0x6040, 0), 0x000F);
}

TEST_F(CoeClient, NormalUploadInOneMessage) {
  EXPECT_EQ(sdo().upload(0x1008, 0), (Bytes{'M', 'A', 'D', 'L', 'N', '1', '5', 'B', 'E'}));
}

TEST_F(CoeClient, SegmentedUploadOverOneKiB) {
  const Bytes big = pattern(1500);  // a 256-byte mailbox carries at most 240 data bytes per segment
  server.dictionary[0x2100].entries[0] = {big, true, "Blob"};
  const std::uint64_t before = server.requests;
  EXPECT_EQ(sdo().upload(0x2100, 0), big);
  EXPECT_GE(server.requests - before, 1 + 1500 / 247) << "one initiate plus the segments";
}

TEST_F(CoeClient, SegmentedDownloadOverOneKiB) {
  server.dictionary[0x2100].entries[0] = {Bytes(3000), true, "Blob"};
  const Bytes big = pattern(3000);
  sdo().download(0x2100, 0, big);
  EXPECT_EQ(server.dictionary[0x2100].entries[0].value, big);
}

TEST_F(CoeClient, ShortSegmentCarriesItsUnusedByteCount) {
  // 240 bytes fit the initiate; the 3 left go in one minimum-size (7-byte) segment.
  const Bytes data = pattern(243);
  server.dictionary[0x2101].entries[0] = {Bytes(243), true, "Odd"};
  sdo().download(0x2101, 0, data);
  EXPECT_EQ(server.dictionary[0x2101].entries[0].value, data);
  EXPECT_EQ(sdo().upload(0x2101, 0), data);
}

TEST_F(CoeClient, CompleteAccessUploadPadsSubindexZero) {
  const Bytes all = sdo().upload(0x1C32, 0, true);
  EXPECT_EQ(all, (Bytes{2, 0, 0x02, 0x00, 0x40, 0x42, 0x0F, 0x00}));
  EXPECT_EQ(sdo().upload(0x1C32, 1, true), (Bytes{0x02, 0x00, 0x40, 0x42, 0x0F, 0x00})) << "from subindex 1";
}

TEST_F(CoeClient, CompleteAccessDownloadWritesEverySubindex) {
  sdo().download(0x1C32, 1, Bytes{0x03, 0x00, 0xA0, 0x86, 0x01, 0x00}, true);
  EXPECT_EQ(server.dictionary[0x1C32].entries[1].value, (Bytes{0x03, 0x00}));
  EXPECT_EQ(sdo().upload_value<std::uint32_t>(0x1C32, 2), 100000u);
}

TEST_F(CoeClient, AbortsAreDecoded) {
  try {
    sdo().upload(0x5FFF, 0);
    FAIL() << "no abort";
  } catch (const SdoAbort& e) {
    EXPECT_EQ(e.code(), 0x06020000u);
    EXPECT_EQ(e.index(), 0x5FFF);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
  try {
    sdo().upload(0x6040, 7);
    FAIL() << "no abort";
  } catch (const SdoAbort& e) {
    EXPECT_EQ(e.code(), 0x06090011u);
    EXPECT_EQ(e.subindex(), 7);
  }
  try {
    sdo().download_value<std::uint32_t>(0x1000, 0, 1);
    FAIL() << "no abort";
  } catch (const SdoAbort& e) {
    EXPECT_EQ(e.code(), 0x06010002u);
  }
  EXPECT_EQ(sdo().upload_value<std::uint8_t>(0x6060, 0), 0x08) << "the mailbox still works after aborts";
}

TEST_F(CoeClient, AbortTextsCoverTheCodesDrivesUse) {
  for (std::uint32_t code : {0x05030000u, 0x06010001u, 0x06010002u, 0x06020000u, 0x06040041u, 0x06070010u, 0x06090011u,
                             0x06090030u, 0x08000000u, 0x08000022u}) {
    EXPECT_NE(sdo_abort_text(code), "Unknown abort code") << std::hex << code;
  }
  EXPECT_EQ(sdo_abort_text(0x12345678), "Unknown abort code");
}

TEST_F(CoeClient, OdListIsReassembledFromFragments) {
  for (std::uint16_t i = 0; i < 200; ++i) server.dictionary[static_cast<std::uint16_t>(0x3000 + i)].entries[0] = {{1}, true, "x"};
  const auto list = sdo().od_list();
  std::vector<std::uint16_t> expected;
  for (const auto& [index, o] : server.dictionary) expected.push_back(index);
  EXPECT_EQ(list, expected) << "400+ bytes need more than one 256-byte mailbox";
}

TEST_F(CoeClient, ObjectAndEntryDescriptions) {
  const ObjectDescription od = sdo().object_description(0x1C32);
  EXPECT_EQ(od.index, 0x1C32);
  EXPECT_EQ(od.object_code, 9);
  EXPECT_EQ(od.max_subindex, 2);
  EXPECT_EQ(od.name, "SM output parameter");
  const EntryDescription ed = sdo().entry_description(0x1C32, 2);
  EXPECT_EQ(ed.subindex, 2);
  EXPECT_EQ(ed.bit_length, 32);
  EXPECT_EQ(ed.name, "Cycle time");
  try {
    sdo().object_description(0x5FFF);
    FAIL() << "no SDO info error";
  } catch (const SdoAbort& e) {
    EXPECT_EQ(e.code(), 0x06020000u);
  }
}

TEST_F(CoeClient, EmergencyBeforeTheReplyIsQueued) {
  server.queue_emergency(0x7500, 0x81);
  EXPECT_EQ(sdo().upload_value<std::uint8_t>(0x6060, 0), 0x08);
  auto& em = sdo().mailbox().emergencies();
  ASSERT_EQ(em.size(), 1u);
  EXPECT_EQ(em.front().error_code, 0x7500);
  EXPECT_EQ(em.front().error_register, 0x81);
  EXPECT_EQ(em.front().station, 0x1001);
  EXPECT_EQ(em.front().data, (std::array<std::uint8_t, 5>{1, 2, 3, 4, 5}));
}

TEST_F(CoeClient, LostReplyIsRecoveredWithARepeatRequest) {
  SdoClient& client = sdo();
  const auto& mb = client.mailbox().config();
  // Lose the first reply frame that carries a full SM1 read: the ESC has emptied SM1 by then.
  int dropped = 0;
  line.drop_reply = [&](std::span<const std::uint8_t> frame) {
    const bool sm1_read = frame.size() > 26 && frame[16] == 4 /* FPRD */ &&
                          (frame[20] | (frame[21] << 8)) == mb.tx_offset &&
                          ((frame[22] | (frame[23] << 8)) & 0x7FF) == mb.tx_size && frame[26 + mb.tx_size] == 1;
    if (sm1_read && dropped == 0) {
      ++dropped;
      return true;
    }
    return false;
  };
  EXPECT_EQ(client.upload_value<std::uint16_t>(0x6040, 0), 0x0000);
  EXPECT_EQ(dropped, 1);
  EXPECT_EQ(client.mailbox().repeat_requests(), 1u);
  EXPECT_EQ(server.repeats, 1u);
}

TEST_F(CoeClient, MailboxErrorReplyBecomesMailboxError) {
  MailboxClient& mb = sdo().mailbox();
  const Bytes eoe{0, 0, 0, 0};
  mb.send(mailbox_type::kEoE, eoe);
  try {
    mb.receive(mailbox_type::kEoE);
    FAIL() << "no mailbox error";
  } catch (const MailboxError& e) {
    EXPECT_EQ(e.code(), 0x0002);
    EXPECT_NE(std::string(e.what()).find("UNSUPPORTEDPROTOCOL"), std::string::npos);
  }
}

TEST_F(CoeClient, SilentSlaveTimesOut) {
  line.after_frame = nullptr;
  const Nanos start = line.clock().now();
  EXPECT_THROW(sdo().upload(0x6060, 0), MailboxError);
  EXPECT_GE(line.clock().now() - start, 100'000'000) << "waited the timeout twice (before and after the repeat request)";
}

TEST_F(CoeClient, OversizeMessageIsRefusedBeforeSending) {
  const Bytes big(300);
  EXPECT_THROW(sdo().mailbox().send(mailbox_type::kCoE, big), MailboxError);
}

}  // namespace
}  // namespace vdrive::master
