// Store parameters (1010h, A6B L8784-L8904): "save" persists the drive's writable objects to its
// file, a restart loads them, a crash mid-write loses nothing, other values are refused.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/firmware/coe_test_client.hpp"
#include "tests/firmware/mailbox_test_bench.hpp"
#include "vdrive/firmware/coe/parameter_store.hpp"

namespace vdrive::firmware::mailbox_test {
namespace {

constexpr std::uint32_t kSave = 0x65766173;  // "save", little-endian on the wire: 73 61 76 65

profile::ProductProfile a6b() { return profile::load_profile("a6b"); }

const od::EntryDesc* writable_u16(const od::Dictionary& d) {
  for (const od::ObjectDesc& o : d.objects()) {
    if (o.index < 0x3000) continue;
    for (const od::EntryDesc& e : o.entries) {
      if ((e.type == od::DataType::Unsigned16 || e.type == od::DataType::Integer16) &&
          (e.access & od::access::kWritePreOp) && e.min && e.max && *e.max > *e.min + 2 &&
          *e.min >= 0) {
        return &e;
      }
    }
  }
  return nullptr;
}

std::string params_file(const Bench& b, const std::string& dir) {
  char name[32];
  std::snprintf(name, sizeof(name), "-%08x.params", b.product.identity.serial);
  return dir + "/" + b.product.id + name;
}

TEST(ParameterStore, SaveSurvivesARestart) {
  TempDir state;
  std::uint64_t saved = 0;
  const od::EntryDesc* e = nullptr;
  {
    Bench b(a6b(), {}, state.path);
    b.to_preop();
    e = writable_u16(b.dictionary);
    ASSERT_NE(e, nullptr);
    EXPECT_NE(b.objects.raw(*e)[0], 0xEE);
    saved = static_cast<std::uint64_t>(*e->min + 1);
    ASSERT_EQ(sdo_write(b, e->index, e->subindex, le(saved, 2)).abort, 0u);
    EXPECT_EQ(sdo_write(b, 0x1010, 0x01, le(kSave, 4)).abort, 0u);
    EXPECT_EQ(sdo_read(b, 0x1010, 0x01).data, le(1, 4)) << "reads 1 after the save";
    EXPECT_TRUE(std::filesystem::exists(params_file(b, state.path)));
  }
  Bench restarted(a6b(), {}, state.path);
  restarted.to_preop();
  const od::EntryDesc* again = writable_u16(restarted.dictionary);
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(sdo_read(restarted, again->index, again->subindex).data, le(saved, 2));
}

TEST(ParameterStore, UnsavedChangesAreLostAtPowerOn) {
  TempDir state;
  Bench b(a6b(), {}, state.path);
  b.to_preop();
  const od::EntryDesc* e = writable_u16(b.dictionary);
  ASSERT_NE(e, nullptr);
  const std::vector<std::uint8_t> factory = sdo_read(b, e->index, e->subindex).data;
  ASSERT_EQ(sdo_write(b, e->index, e->subindex, le(static_cast<std::uint64_t>(*e->min + 2), 2)).abort, 0u);
  b.request_state(ecat::AlState::Init);
  b.objects.reset_to_defaults();  // what SlaveFirmware::power_on does first
  b.module.power_on(0);
  b.to_preop();
  EXPECT_EQ(sdo_read(b, e->index, e->subindex).data, factory);
}

TEST(ParameterStore, OtherValuesThanSaveAreRefused) {
  TempDir state;
  Bench b(a6b(), {}, state.path);
  b.to_preop();
  EXPECT_EQ(sdo_read(b, 0x1010, 0x01).data, le(1, 4)) << "after power-on";
  EXPECT_EQ(sdo_write(b, 0x1010, 0x01, le(0x12345678, 4)).abort, 0x08000020u);
  EXPECT_EQ(sdo_write(b, 0x1010, 0x00, {0x01}).abort, 0x06010002u) << "subindex 0 is read-only";
  b.module.power_on(0);
  EXPECT_FALSE(std::filesystem::exists(params_file(b, state.path))) << "nothing was saved";
}

TEST(ParameterStore, TornWriteLeavesTheStoredValuesIntact) {
  TempDir state;
  std::uint64_t saved = 0;
  std::string file;
  {
    Bench b(a6b(), {}, state.path);
    b.to_preop();
    const od::EntryDesc* e = writable_u16(b.dictionary);
    saved = static_cast<std::uint64_t>(*e->min + 1);
    ASSERT_EQ(sdo_write(b, e->index, e->subindex, le(saved, 2)).abort, 0u);
    ASSERT_EQ(sdo_write(b, 0x1010, 0x01, le(kSave, 4)).abort, 0u);
    file = params_file(b, state.path);
  }
  // A crash in the middle of the next save: the temporary file is half written.
  {
    std::ofstream tmp(file + ".tmp", std::ios::binary);
    tmp << "VDPARAM1\x05\x00";
  }
  {
    Bench b(a6b(), {}, state.path);
    b.to_preop();
    const od::EntryDesc* e = writable_u16(b.dictionary);
    EXPECT_EQ(sdo_read(b, e->index, e->subindex).data, le(saved, 2));
  }
  // A damaged target (not something our writer leaves, but a disk can) is ignored: defaults.
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 3);
  Bench b(a6b(), {}, state.path);
  b.to_preop();
  const od::EntryDesc* e = writable_u16(b.dictionary);
  EXPECT_EQ(b.objects.raw(*e)[0], e->default_value.at(0));
}

TEST(ParameterStore, ProductsWithout1010hHaveNoStore) {
  for (const char* id : {"ds5c1", "ds1000a"}) {
    TempDir state;
    Bench b(profile::load_profile(id), {}, state.path);
    b.to_preop();
    EXPECT_EQ(sdo_write(b, 0x1010, 0x01, le(kSave, 4)).abort, 0x06020000u) << id;
    EXPECT_TRUE(std::filesystem::is_empty(state.path)) << id;
  }
}

TEST(ParameterStore, Crc32MatchesTheStandardCheckValue) {
  const std::string check = "123456789";
  EXPECT_EQ(coe::crc32(reinterpret_cast<const std::uint8_t*>(check.data()), check.size()),
            0xCBF43926u);
}

}  // namespace
}  // namespace vdrive::firmware::mailbox_test
