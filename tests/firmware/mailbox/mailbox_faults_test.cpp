// Injected mailbox faults on the mailbox bench, seen on the wire: the wrong toggle bit in a
// segmented transfer (which needs an object longer than a mailbox: a test-only dictionary, as
// none of the three products has one), and how each fault is used up. The master's reaction to
// lost, duplicated and aborted replies: tests/master/mailbox_faults_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/firmware/coe_test_client.hpp"
#include "tests/firmware/mailbox_test_bench.hpp"

namespace vdrive::firmware::mailbox_test {
namespace {

constexpr std::size_t kBlobBytes = 600;
constexpr std::uint8_t kToggle = 0x10;

// DS1000A-EC's profile (128-byte mailbox) with a dictionary holding one long octet string.
struct BlobProduct {
  BlobProduct() {
    product = profile::load_profile("ds1000a");
    product.id = "mbxfault";
    product.rx_pdos.clear();  // the test dictionary has no PDO objects
    product.tx_pdos.clear();
    std::filesystem::create_directories(dir.path + "/mbxfault");
    std::ofstream y(dir.path + "/mbxfault/objects.yaml");
    y << "product: mbxfault\nmanual: \"none\"\ntable_lines: \"-\"\nobject_count: 1\nentry_count: 1\nnotes: []\nobjects:\n"
         "  - index: 0x2000\n    name: \"Blob\"\n    object_code: VAR\n    line: 1\n    entries:\n"
         "      - {subindex: 0, name: \"Blob\", data_type: OS, access: rw, pdo: \"no\", default: \""
      << std::string(kBlobBytes, 'x') << "\", min: null, max: null, units: null, line: 1}\n";
  }
  TempDir dir;
  profile::ProductProfile product;
};

TEST(MailboxFaultsBench, ToggleErrorFlipsTheNextUploadSegmentResponseOnly) {
  BlobProduct t;
  Bench b(t.product, t.dir.path);
  b.to_preop();
  b.module.set_faults({.toggle_error = true});
  auto r = b.exchange(kCoE, sdo_payload(0x40, 0x2000, 0));  // initiate upload: not a segment
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->at(8), 0x41) << "normal upload, size indicated, untouched";
  EXPECT_TRUE(b.module.faults().toggle_error) << "still armed";
  r = b.exchange(kCoE, sdo_payload(0x60, 0, 0));  // first segment: toggle 0 due
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->at(8) >> 5, 0) << "an upload segment response";
  EXPECT_EQ(r->at(8) & kToggle, kToggle) << "wrong toggle: a client aborts 05030000h";
  EXPECT_FALSE(b.module.faults().toggle_error) << "used up";
  r = b.exchange(kCoE, sdo_payload(0x70, 0, 0));  // the server goes on: toggle 1 is right
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->at(8) & kToggle, kToggle);
}

TEST(MailboxFaultsBench, ToggleErrorFlipsADownloadSegmentResponse) {
  BlobProduct t;
  Bench b(t.product, t.dir.path);
  b.to_preop();
  std::vector<std::uint8_t> p = sdo_payload(0x21, 0x2000, 0, {static_cast<std::uint8_t>(kBlobBytes & 0xFF),
                                                              static_cast<std::uint8_t>(kBlobBytes >> 8), 0, 0});
  p.resize(b.sm0_length() - 6u, 0x55);
  auto r = b.exchange(kCoE, p);
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->at(8), 0x60);
  b.module.set_faults({.toggle_error = true});
  r = b.exchange(kCoE, {0x00, 0x20, 0x00, 1, 2, 3, 4, 5, 6, 7});  // segment, toggle 0
  ASSERT_TRUE(r.has_value() && !is_abort(*r));
  EXPECT_EQ(r->at(8), 0x20 | kToggle) << "download segment response with toggle 1";
}

TEST(MailboxFaultsBench, AbortCodeAnswersASegmentRequestAndEndsTheTransfer) {
  BlobProduct t;
  Bench b(t.product, t.dir.path);
  b.to_preop();
  auto r = b.exchange(kCoE, sdo_payload(0x40, 0x2000, 0));
  ASSERT_TRUE(r.has_value());
  b.module.set_faults({.abort_code = 0x05040000});
  r = b.exchange(kCoE, sdo_payload(0x60, 0, 0));
  ASSERT_TRUE(r.has_value() && is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05040000u);
  EXPECT_EQ(b.module.faults().abort_code, 0u);
  r = b.exchange(kCoE, sdo_payload(0x70, 0, 0));  // the transfer is over
  ASSERT_TRUE(r.has_value() && is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05040001u);
}

TEST(MailboxFaultsBench, LostRepliesNeverReachSm1AndCountDown) {
  Bench b(profile::load_profile("ds5c1"));
  b.to_preop();
  b.module.set_faults({.lose_replies = 2, .duplicate_replies = 1});
  EXPECT_FALSE(b.exchange(kCoE, sdo_payload(0x40, 0x1018, 1)).has_value());
  EXPECT_EQ(b.module.faults().lose_replies, 1);
  EXPECT_FALSE(b.exchange(kCoE, sdo_payload(0x40, 0x1018, 2)).has_value());
  EXPECT_EQ(b.module.faults().lose_replies, 0);
  // Duplicated: the reply, then the same message (same counter) once the master read it.
  const auto first = b.exchange(kCoE, sdo_payload(0x40, 0x1018, 1));
  ASSERT_TRUE(first.has_value());
  const auto copy = b.receive();
  ASSERT_TRUE(copy.has_value());
  EXPECT_EQ(*copy, *first);
  EXPECT_FALSE(b.receive().has_value()) << "written twice, not more";
  EXPECT_EQ(b.module.faults().duplicate_replies, 0);
}

}  // namespace
}  // namespace vdrive::firmware::mailbox_test
