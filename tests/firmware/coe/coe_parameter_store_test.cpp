// Store parameters (1010h, A6B L8784-L8904): "save" persists the drive's writable objects to its
// file, a restart loads them, a crash mid-write loses nothing, other values are refused.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <span>

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

// kill -9 at any moment of a save: a forked child saves one generation after another (two entries
// written with the same value, so a file mixing two saves would show), the parent kills it after a
// random delay, and a restart must load one whole generation: never a torn file, never defaults.
TEST(ParameterStore, KilledAtAnyMomentOfASaveARestartLoadsOneWholeGeneration) {
  TempDir state;
  const profile::ProductProfile product = a6b();  // loaded once: the restarts are many
  // Two writable U16 entries of the A6B's vendor range, by index (the dictionary is the Bench's).
  std::uint16_t index[2] = {};
  std::uint8_t sub[2] = {};
  {
    Bench b(product, {}, state.path);
    int found = 0;
    for (const od::ObjectDesc& o : b.dictionary.objects()) {
      for (const od::EntryDesc& e : o.entries) {
        if (found == 2 || e.index < 0x3000 || e.type != od::DataType::Unsigned16 || !(e.access & od::access::kWritePreOp))
          continue;
        index[found] = e.index, sub[found] = e.subindex;
        ++found;
      }
    }
    ASSERT_EQ(found, 2);
  }
  auto entry = [&](Bench& b, int k) -> std::span<std::uint8_t> {
    return b.objects.raw(*b.dictionary.find(index[k], sub[k]));
  };
  auto put = [&](Bench& b, std::uint16_t v) {
    for (int k = 0; k < 2; ++k) {
      entry(b, k)[0] = static_cast<std::uint8_t>(v);
      entry(b, k)[1] = static_cast<std::uint8_t>(v >> 8);
    }
  };
  {
    Bench b(product, {}, state.path);
    coe::ParameterStore store(b.product, b.objects, state.path);
    put(b, 0x7777);  // generation 0, on disk before the first kill
    ASSERT_TRUE(store.save());
  }
  // Each kill costs two drive start-ups (about 0.5 s on a loaded 2-core VM); about half of them
  // land inside a save (a temporary file is left), so 60 hit the write itself some 30 times.
  constexpr int kKills = 60;
  std::mt19937 random(20261127);
  int changed = 0, unchanged = 0, temp_left = 0;
  std::uint16_t previous = 0x7777;
  for (int i = 0; i < kKills; ++i) {
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      Bench b(product, {}, state.path);
      coe::ParameterStore store(b.product, b.objects, state.path);
      const char go = 1;
      if (::write(ready[1], &go, 1) != 1) ::_exit(2);
      for (std::uint16_t g = 0;; ++g) {
        put(b, static_cast<std::uint16_t>(0x5A00 | (g & 0xFF)));
        if (!store.save()) ::_exit(3);
      }
    }
    ::close(ready[1]);
    char go = 0;
    ASSERT_EQ(::read(ready[0], &go, 1), 1) << "the child did not start";
    ::close(ready[0]);
    ::usleep(std::uniform_int_distribution<useconds_t>(0, 4000)(random));
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child ended on its own: " << status;
    // A temporary file left behind: this kill landed between its open and the rename.
    for (const auto& f : std::filesystem::directory_iterator(state.path)) {
      if (f.path().extension() == ".tmp") {
        ++temp_left;
        std::filesystem::remove(f.path());
      }
    }
    Bench restarted(product, {}, state.path);
    const auto a = entry(restarted, 0), b = entry(restarted, 1);
    const auto value = static_cast<std::uint16_t>(a[0] | a[1] << 8);
    ASSERT_TRUE(a[0] == b[0] && a[1] == b[1]) << "iteration " << i << ": two generations mixed";
    ASSERT_TRUE(value == 0x7777 || (value >> 8) == 0x5A) << "iteration " << i << ": defaults, the file was not loaded";
    (value == previous ? unchanged : changed) += 1;
    previous = value;
  }
  std::printf("%d kills: %d restarts loaded a newer generation, %d the one before, %d left a temporary file\n",
              kKills, changed, unchanged, temp_left);
  EXPECT_GT(temp_left, 0) << "no kill landed inside a save (between the temporary file's open and its rename)";
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
