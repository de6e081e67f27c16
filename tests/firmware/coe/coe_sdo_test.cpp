// CoE SDO transfers against each product's dictionary: expedited, normal and segmented up- and
// download (over 1 KiB with a test-only dictionary), complete access per product, and each class
// of abort the store and the protocol produce.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/firmware/coe_test_client.hpp"
#include "tests/firmware/mailbox_test_bench.hpp"

namespace vdrive::firmware::mailbox_test {
namespace {

profile::ProductProfile load(const std::string& id) { return profile::load_profile(id); }

// A numeric entry writable in PreOp with a range narrower than its type, outside the objects
// whose writes have side effects (PDO, sync, store).
const od::EntryDesc* ranged_writable(const od::Dictionary& d) {
  for (const od::ObjectDesc& o : d.objects()) {
    if (o.index < 0x2000) continue;
    for (const od::EntryDesc& e : o.entries) {
      const bool numeric = e.type == od::DataType::Unsigned16 || e.type == od::DataType::Unsigned32 ||
                           e.type == od::DataType::Integer16 || e.type == od::DataType::Integer32;
      if (numeric && (e.access & od::access::kWritePreOp) && e.min && e.max && *e.max > *e.min &&
          *e.max < 30000 && *e.min >= 0) {
        return &e;
      }
    }
  }
  return nullptr;
}

class SdoOnProduct : public ::testing::TestWithParam<std::string> {};

TEST_P(SdoOnProduct, ExpeditedUploadOfTheIdentity) {
  Bench b(load(GetParam()));
  b.to_preop();
  const SdoResult r = sdo_read(b, 0x1018, 0x01);
  EXPECT_EQ(r.abort, 0u);
  EXPECT_TRUE(r.expedited);
  EXPECT_EQ(r.data, le(b.product.identity.vendor_id, 4));
  EXPECT_EQ(sdo_read(b, 0x1018, 0x02).data, le(b.product.identity.product_code, 4));
  EXPECT_EQ(sdo_read(b, 0x1000, 0x00).data, le(b.product.identity.device_type, 4));
}

TEST_P(SdoOnProduct, NormalUploadOfTheDeviceName) {
  Bench b(load(GetParam()));
  b.to_preop();
  const SdoResult r = sdo_read(b, 0x1008, 0x00);
  EXPECT_EQ(r.abort, 0u);
  ASSERT_GT(b.product.identity.device_name.size(), 4u);
  EXPECT_FALSE(r.expedited);
  EXPECT_EQ(std::string(r.data.begin(), r.data.end()), b.product.identity.device_name);
}

TEST_P(SdoOnProduct, DownloadThenUploadReadsBack) {
  Bench b(load(GetParam()));
  b.to_preop();
  const od::EntryDesc* e = ranged_writable(b.dictionary);
  ASSERT_NE(e, nullptr);
  const std::size_t n = e->bit_length / 8;
  const auto value = static_cast<std::uint64_t>(*e->min + (*e->max - *e->min) / 2);
  EXPECT_EQ(sdo_write(b, e->index, e->subindex, le(value, n)).abort, 0u);
  EXPECT_EQ(sdo_read(b, e->index, e->subindex).data, le(value, n));
  // The same value by normal transfer (size in the command, data after it).
  std::vector<std::uint8_t> p = sdo_payload(0x21, e->index, e->subindex, le(n, 4));
  const std::vector<std::uint8_t> v = le(*e->min, n);
  p.insert(p.end(), v.begin(), v.end());
  auto reply = b.exchange(kCoE, p);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->at(8), 0x60);
  EXPECT_EQ(sdo_read(b, e->index, e->subindex).data, v);
}

TEST_P(SdoOnProduct, AbortsFromTheObjectDictionary) {
  Bench b(load(GetParam()));
  b.to_preop();
  std::uint16_t missing = 0x5FFF;
  while (b.dictionary.find(missing) != nullptr) --missing;
  EXPECT_EQ(sdo_read(b, missing, 0).abort, 0x06020000u) << "object does not exist";
  EXPECT_EQ(sdo_read(b, 0x1018, 0x55).abort, 0x06090011u) << "subindex does not exist";
  EXPECT_EQ(sdo_write(b, 0x1018, 0x01, le(1, 4)).abort, 0x06010002u) << "read-only";
  const od::EntryDesc* e = ranged_writable(b.dictionary);
  ASSERT_NE(e, nullptr);
  const std::size_t n = e->bit_length / 8;
  EXPECT_EQ(sdo_write(b, e->index, e->subindex, le(0, n == 4 ? 2 : 4)).abort, 0x06070010u)
      << "length mismatch";
  EXPECT_EQ(sdo_write(b, e->index, e->subindex, le(static_cast<std::uint64_t>(*e->max) + 1, n)).abort,
            0x06090031u)
      << "value too high";
}

// DS5C1 P0-27 (201Bh) and P0-29 (201Dh): chapter 5 documents the stop modes 0-5 (L2169-L2194) where
// App. 1.1 lists "0、2" (L8677, L8680); every value chapter 5 describes is taken, 6 is too high.
TEST_P(SdoOnProduct, EveryAbortIsCountedWithTheLastOneKept) {
  Bench b(load(GetParam()));
  b.to_preop();
  EXPECT_EQ(b.aborts.count, 0u);
  std::uint16_t missing = 0x5FFF;
  while (b.dictionary.find(missing) != nullptr) --missing;
  (void)sdo_read(b, missing, 0);
  EXPECT_EQ(b.aborts.count, 1u);
  EXPECT_EQ(b.aborts.index, missing);
  EXPECT_EQ(b.aborts.code, 0x06020000u);
  (void)sdo_write(b, 0x6041, 0, le(0, 2));  // read-only
  EXPECT_EQ(b.aborts.count, 2u);
  EXPECT_EQ(b.aborts.index, 0x6041);
  EXPECT_EQ(b.aborts.code, 0x06010002u);
  (void)sdo_read(b, 0x1018, 1);  // answered: not an abort
  EXPECT_EQ(b.aborts.count, 2u);
}

TEST(SdoDs5c1, StopModeParametersTakeTheSixModesOfChapter5) {
  Bench b(load("ds5c1"));
  b.to_preop();
  for (const std::uint16_t index : {std::uint16_t{0x201B}, std::uint16_t{0x201D}}) {
    for (std::uint64_t mode = 0; mode <= 5; ++mode) {
      EXPECT_EQ(sdo_write(b, index, 0, le(mode, 2)).abort, 0u) << std::hex << index << " = " << mode;
      EXPECT_EQ(sdo_read(b, index, 0).data, le(mode, 2)) << std::hex << index;
    }
    EXPECT_EQ(sdo_write(b, index, 0, le(6, 2)).abort, 0x06090031u) << std::hex << index << ": value too high";
  }
}

TEST_P(SdoOnProduct, ProtocolAborts) {
  Bench b(load(GetParam()));
  b.to_preop();
  // Command specifier 7 does not exist.
  auto r = b.exchange(kCoE, sdo_payload(0xE0, 0x1018, 1));
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05040001u);
  // A segment with no transfer in progress.
  r = b.exchange(kCoE, sdo_payload(0x60, 0, 0));
  ASSERT_TRUE(r.has_value() && is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05040001u);
  r = b.exchange(kCoE, sdo_payload(0x00, 0, 0));
  ASSERT_TRUE(r.has_value() && is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05040001u);
  // An abort from the master is not answered.
  ASSERT_EQ(b.send(message(kCoE, 7, sdo_payload(0x80, 0x1018, 1, le(0x08000000, 4)))), 1);
  EXPECT_FALSE(b.receive().has_value());
}

TEST_P(SdoOnProduct, CompleteAccessIsRefusedWithTheProductsCode) {
  Bench b(load(GetParam()));
  b.to_preop();
  ASSERT_EQ(b.product.coe_details & 0x20, 0) << "none of the three products has complete access";
  // A6B: its abort table has no 06010004h; 06010000h "unsupported access" (L4411-L4552).
  const std::uint32_t expected = GetParam() == "a6b" ? 0x06010000u : 0x06010004u;
  EXPECT_EQ(sdo_read(b, 0x1018, 0, true).abort, expected);
  EXPECT_EQ(sdo_write(b, 0x1C12, 0, {1, 0, 0x00, 0x16}, true).abort, expected);
  EXPECT_EQ(expected, b.product.complete_access_abort);  // profile.yaml complete_access_abort
}

// The refusal is the profile's complete_access_abort, whatever the product.
TEST(SdoCompleteAccess, RefusalCodeComesFromTheProfile) {
  profile::ProductProfile p = load("ds5c1");
  p.complete_access_abort = 0x06010000;
  Bench b(p);
  b.to_preop();
  EXPECT_EQ(sdo_read(b, 0x1018, 0, true).abort, 0x06010000u);
}

INSTANTIATE_TEST_SUITE_P(Products, SdoOnProduct, ::testing::Values("a6b", "ds5c1", "ds1000a"));

// ---- a test-only product: complete access and an object over 1 KiB ----------------------------

constexpr std::size_t kBlobBytes = 1500;

// DS1000A-EC's profile with complete access advertised and a dictionary of its own.
struct TestProduct {
  TestProduct() {
    product = profile::load_profile("ds1000a");
    product.id = "coetest";
    product.coe_details |= 0x20;
    product.rx_pdos.clear();  // the test dictionary has no PDO objects
    product.tx_pdos.clear();
    std::filesystem::create_directories(dir.path + "/coetest");
    std::ofstream y(dir.path + "/coetest/objects.yaml");
    y << "product: coetest\nmanual: \"none\"\ntable_lines: \"-\"\nobject_count: 2\nentry_count: 5\nnotes: []\nobjects:\n"
         "  - index: 0x2000\n    name: \"Blob\"\n    object_code: VAR\n    line: 1\n    entries:\n"
         "      - {subindex: 0, name: \"Blob\", data_type: OS, access: rw, pdo: \"no\", default: \""
      << std::string(kBlobBytes, 'x')
      << "\", min: null, max: null, units: null, line: 1}\n"
         "  - index: 0x2001\n    name: \"Table\"\n    object_code: ARRAY\n    line: 2\n    entries:\n"
         "      - {subindex: 0, name: \"Count\", data_type: U8, access: rw, pdo: \"no\", default: 3, min: 0, max: 3, units: null, line: 1}\n"
         "      - {subindex: 1, name: \"A\", data_type: U16, access: rw, pdo: \"no\", default: 0x1111, min: null, max: null, units: null, line: 1}\n"
         "      - {subindex: 2, name: \"B\", data_type: U16, access: rw, pdo: \"no\", default: 0x2222, min: null, max: null, units: null, line: 1}\n"
         "      - {subindex: 3, name: \"C\", data_type: U16, access: rw, pdo: \"no\", default: 0x3333, min: null, max: null, units: null, line: 1}\n";
  }
  TempDir dir;
  profile::ProductProfile product;
};

TEST(SdoTestProduct, SegmentedDownloadAndUploadOverOneKiB) {
  TestProduct t;
  Bench b(t.product, t.dir.path);
  b.to_preop();
  std::vector<std::uint8_t> blob(kBlobBytes);
  for (std::size_t i = 0; i < blob.size(); ++i) blob[i] = static_cast<std::uint8_t>(i * 7 + 3);
  const SdoResult w = sdo_write(b, 0x2000, 0, blob);
  EXPECT_EQ(w.abort, 0u);
  EXPECT_GE(w.segments, 10) << "a 128-byte mailbox needs many segments";
  const SdoResult r = sdo_read(b, 0x2000, 0);
  EXPECT_EQ(r.abort, 0u);
  EXPECT_GE(r.segments, 10);
  EXPECT_EQ(r.data, blob);
}

TEST(SdoTestProduct, WrongToggleAbortsTheTransfer) {
  TestProduct t;
  Bench b(t.product, t.dir.path);
  b.to_preop();
  auto r = b.exchange(kCoE, sdo_payload(0x40, 0x2000, 0));
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->at(8), 0x41) << "normal upload, size indicated";
  r = b.exchange(kCoE, sdo_payload(0x70, 0, 0));  // toggle 1 where 0 is due
  ASSERT_TRUE(r.has_value() && is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05030000u);
  EXPECT_EQ(u16_at(*r, 9), 0x2000);
  // The transfer is over: the next segment has nothing to continue.
  r = b.exchange(kCoE, sdo_payload(0x60, 0, 0));
  ASSERT_TRUE(r.has_value() && is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05040001u);
  // Download side: a segment with the wrong toggle.
  std::vector<std::uint8_t> p = sdo_payload(0x21, 0x2000, 0, le(kBlobBytes, 4));
  p.resize(b.sm0_length() - 6u, 0x55);
  r = b.exchange(kCoE, p);
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->at(8), 0x60);
  r = b.exchange(kCoE, {0x00, 0x20, 0x10, 1, 2, 3, 4, 5, 6, 7});
  ASSERT_TRUE(r.has_value() && is_abort(*r));
  EXPECT_EQ(u32_at(*r, 12), 0x05030000u);
}

TEST(SdoTestProduct, CompleteAccessUploadPadsSubindexZero) {
  TestProduct t;
  Bench b(t.product, t.dir.path);
  b.to_preop();
  const SdoResult r = sdo_read(b, 0x2001, 0, true);
  EXPECT_EQ(r.abort, 0u);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{3, 0, 0x11, 0x11, 0x22, 0x22, 0x33, 0x33}));
  const SdoResult from1 = sdo_read(b, 0x2001, 1, true);
  EXPECT_EQ(from1.data, (std::vector<std::uint8_t>{0x11, 0x11, 0x22, 0x22, 0x33, 0x33}));
}

TEST(SdoTestProduct, CompleteAccessDownloadWritesEveryEntry) {
  TestProduct t;
  Bench b(t.product, t.dir.path);
  b.to_preop();
  EXPECT_EQ(sdo_write(b, 0x2001, 0, {2, 0, 0xAA, 0x0A, 0xBB, 0x0B}, true).abort, 0u);
  EXPECT_EQ(sdo_read(b, 0x2001, 0).data, (std::vector<std::uint8_t>{2}));
  EXPECT_EQ(sdo_read(b, 0x2001, 1).data, (std::vector<std::uint8_t>{0xAA, 0x0A}));
  EXPECT_EQ(sdo_read(b, 0x2001, 2).data, (std::vector<std::uint8_t>{0xBB, 0x0B}));
  EXPECT_EQ(sdo_read(b, 0x2001, 3).data, (std::vector<std::uint8_t>{0x33, 0x33}));
  // Data that does not match the entries: too short.
  EXPECT_EQ(sdo_write(b, 0x2001, 0, {3, 0, 1, 2, 3}, true).abort, 0x06070013u);
}

}  // namespace
}  // namespace vdrive::firmware::mailbox_test
