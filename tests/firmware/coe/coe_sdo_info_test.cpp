// SDO Information (ETG.1000.6 5.6.3) against each product's dictionary: OD lists whose counts
// equal the dictionary, fragmented replies, object and entry descriptions, and the error request.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/firmware/coe_test_client.hpp"
#include "tests/firmware/mailbox_test_bench.hpp"

namespace vdrive::firmware::mailbox_test {
namespace {

profile::ProductProfile load(const std::string& id) { return profile::load_profile(id); }

std::vector<std::uint8_t> info_request(std::uint8_t opcode, std::vector<std::uint8_t> data) {
  std::vector<std::uint8_t> p{0x00, 0x80, opcode, 0x00, 0x00, 0x00};
  p.insert(p.end(), data.begin(), data.end());
  return p;
}

struct InfoReply {
  std::uint8_t opcode = 0;
  std::vector<std::uint8_t> data;  // fragments joined
  int fragments = 0;
};

// Sends one request and collects every fragment, checking "fragments left" counts down to 0 and
// the incomplete bit is set on all but the last.
InfoReply info(Bench& b, std::uint8_t opcode, std::vector<std::uint8_t> data) {
  InfoReply out;
  auto r = b.exchange(kCoE, info_request(opcode, std::move(data)));
  int expected_left = -1;
  while (r.has_value()) {
    EXPECT_EQ(u16_at(*r, 6) >> 12, 8) << "CoE service 8";
    out.opcode = r->at(8) & 0x7F;
    const bool incomplete = (r->at(8) & 0x80) != 0;
    const int left = u16_at(*r, 10);
    if (expected_left >= 0) {
      EXPECT_EQ(left, expected_left);
    }
    EXPECT_EQ(incomplete, left > 0);
    out.data.insert(out.data.end(), r->begin() + 12, r->end());
    ++out.fragments;
    if (!incomplete) break;
    expected_left = left - 1;
    r = b.receive();
  }
  EXPECT_GT(out.fragments, 0) << "no reply";
  return out;
}

std::vector<std::uint16_t> indexes(const InfoReply& r) {
  std::vector<std::uint16_t> out;
  for (std::size_t at = 2; at + 1 < r.data.size(); at += 2) out.push_back(u16_at(r.data, at));
  return out;
}

class SdoInfoOnProduct : public ::testing::TestWithParam<std::string> {};

TEST_P(SdoInfoOnProduct, AllObjectsListEqualsTheDictionary) {
  Bench b(load(GetParam()));
  b.to_preop();
  const InfoReply r = info(b, 0x01, {0x01, 0x00});
  EXPECT_EQ(r.opcode, 0x02);
  EXPECT_EQ(u16_at(r.data, 0), 1) << "list type echoed";
  std::vector<std::uint16_t> expected;
  for (const od::ObjectDesc& o : b.dictionary.objects()) expected.push_back(o.index);
  EXPECT_EQ(indexes(r), expected);
  EXPECT_GT(r.fragments, 1) << "hundreds of objects do not fit one mailbox";
}

TEST_P(SdoInfoOnProduct, ListTypeZeroCountsEachList) {
  Bench b(load(GetParam()));
  b.to_preop();
  const InfoReply counts = info(b, 0x01, {0x00, 0x00});
  ASSERT_EQ(counts.data.size(), 12u);
  for (std::uint16_t type = 1; type <= 5; ++type) {
    const InfoReply list = info(b, 0x01, {static_cast<std::uint8_t>(type), 0x00});
    EXPECT_EQ(indexes(list).size(), u16_at(counts.data, 2u * type)) << "list type " << type;
  }
  // Mappable lists hold exactly the objects with a mappable entry.
  std::size_t rx = 0, tx = 0;
  for (const od::ObjectDesc& o : b.dictionary.objects()) {
    bool r = false, t = false;
    for (const od::EntryDesc& e : o.entries) {
      r = r || (e.access & od::access::kRxPdoMappable);
      t = t || (e.access & od::access::kTxPdoMappable);
    }
    rx += r;
    tx += t;
  }
  EXPECT_EQ(u16_at(counts.data, 2), b.dictionary.objects().size());
  EXPECT_EQ(u16_at(counts.data, 4), rx);
  EXPECT_EQ(u16_at(counts.data, 6), tx);
  EXPECT_GT(rx, 0u);
  EXPECT_GT(tx, 0u);
}

TEST_P(SdoInfoOnProduct, ObjectDescriptionOfTheIdentity) {
  Bench b(load(GetParam()));
  b.to_preop();
  const InfoReply r = info(b, 0x03, {0x18, 0x10});
  EXPECT_EQ(r.opcode, 0x04);
  ASSERT_GE(r.data.size(), 6u);
  const od::ObjectDesc* o = b.dictionary.find(0x1018);
  ASSERT_NE(o, nullptr);
  EXPECT_EQ(u16_at(r.data, 0), 0x1018);
  EXPECT_EQ(r.data[4], o->max_subindex());
  EXPECT_EQ(r.data[5], 9) << "RECORD";
  EXPECT_EQ(std::string(r.data.begin() + 6, r.data.end()), o->name);
}

TEST_P(SdoInfoOnProduct, EntryDescriptionWithValueInfo) {
  Bench b(load(GetParam()));
  b.to_preop();
  // 1018:01 vendor id, asking for unit type, default, minimum and maximum.
  const InfoReply r = info(b, 0x05, {0x18, 0x10, 0x01, 0x78});
  EXPECT_EQ(r.opcode, 0x06);
  ASSERT_GE(r.data.size(), 10u);
  const od::EntryDesc* e = b.dictionary.find(0x1018, 1);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(u16_at(r.data, 0), 0x1018);
  EXPECT_EQ(r.data[2], 1);
  EXPECT_EQ(r.data[3], 0x78) << "all four requested items are sent for an integer";
  EXPECT_EQ(u16_at(r.data, 4), 0x0007) << "UNSIGNED32";
  EXPECT_EQ(u16_at(r.data, 6), 32);
  EXPECT_EQ(u16_at(r.data, 8), e->access);
  EXPECT_EQ(u16_at(r.data, 8) & 0x0038, 0) << "read-only in every state";
  // unit type (2), default (4), min (4), max (4), then the name
  const std::size_t name_at = 10 + 2 + 3 * 4;
  EXPECT_EQ(std::vector<std::uint8_t>(r.data.begin() + 12, r.data.begin() + 16),
            le(b.product.identity.vendor_id, 4))
      << "default = the identity";
  EXPECT_EQ(std::string(r.data.begin() + name_at, r.data.end()), e->name);
  // Without value info: just the fixed part and the name.
  const InfoReply plain = info(b, 0x05, {0x18, 0x10, 0x01, 0x00});
  EXPECT_EQ(std::string(plain.data.begin() + 10, plain.data.end()), e->name);
}

TEST_P(SdoInfoOnProduct, ErrorsComeAsTheErrorRequest) {
  Bench b(load(GetParam()));
  b.to_preop();
  std::uint16_t missing = 0x5FFF;
  while (b.dictionary.find(missing) != nullptr) --missing;
  InfoReply r = info(b, 0x03, {static_cast<std::uint8_t>(missing), static_cast<std::uint8_t>(missing >> 8)});
  EXPECT_EQ(r.opcode, 0x07);
  EXPECT_EQ(u32_at(r.data, 0), 0x06020000u);
  r = info(b, 0x05, {0x18, 0x10, 0x55, 0x00});
  EXPECT_EQ(r.opcode, 0x07);
  EXPECT_EQ(u32_at(r.data, 0), 0x06090011u);
  r = info(b, 0x0C, {0x00, 0x00});
  EXPECT_EQ(r.opcode, 0x07);
  EXPECT_EQ(u32_at(r.data, 0), 0x05040001u);
}

TEST_P(SdoInfoOnProduct, AnSdoRequestDropsAListingInProgress) {
  // A small SM1 (40 bytes, allowed by every product's rules) makes the listing long.
  profile::ProductProfile p = load(GetParam());
  p.sync_managers.at(1).length = 40;
  Bench b(p);
  b.to_preop();
  auto first = b.exchange(kCoE, info_request(0x01, {0x01, 0x00}));
  ASSERT_TRUE(first.has_value());
  ASSERT_NE(first->at(8) & 0x80, 0);
  const int total = u16_at(*first, 10) + 1;
  b.counter = static_cast<std::uint8_t>(b.counter >= 7 ? 1 : b.counter + 1);
  ASSERT_EQ(b.send(message(kCoE, b.counter, sdo_payload(0x40, 0x1018, 1))), 1);
  // The fragments already queued still come, then the SDO response, then nothing.
  int fragments = 1;
  std::optional<std::vector<std::uint8_t>> r;
  while ((r = b.receive()).has_value()) {
    if ((u16_at(*r, 6) >> 12) != 8) break;
    ++fragments;
  }
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(u16_at(*r, 6) >> 12, 3) << "SDO response";
  EXPECT_EQ(u32_at(*r, 12), b.product.identity.vendor_id);
  EXPECT_LT(fragments, total);
  EXPECT_FALSE(b.receive().has_value()) << "the listing was dropped";
}

INSTANTIATE_TEST_SUITE_P(Products, SdoInfoOnProduct, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::firmware::mailbox_test
