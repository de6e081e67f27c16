// Factory PDO configuration where the manuals' tables leave it out (od/default_pdo_objects.hpp):
// the dictionary must announce over CoE the same process-data layout the SII announces.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>

#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::od {
namespace {

std::uint32_t value_of(const ObjectStore& s, std::uint16_t index, std::uint8_t sub) {
  std::uint8_t buf[8] = {};
  std::size_t n = 0;
  EXPECT_EQ(s.read(index, sub, buf, n, ecat::AlState::PreOp), SdoAbort::Ok)
      << std::hex << index << ":" << int(sub);
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < n && i < 4; ++i) v |= static_cast<std::uint32_t>(buf[i]) << (8 * i);
  return v;
}

class DefaultPdo : public ::testing::TestWithParam<std::string> {};

// Every profile PDO that has a mapping object maps, over CoE, exactly the profile's entries, and
// 1C12h/1C13h assign the PDOs the profile assigns to SM2/SM3 — whether the value came from the
// manual's table or was filled in from the profile.
TEST_P(DefaultPdo, CoeLayoutEqualsTheProfilesDefaultPdos) {
  const profile::ProductProfile p = profile::load_profile(GetParam());
  const Dictionary d = Dictionary::load(p);
  const ObjectStore s(d);
  for (const auto* list : {&p.rx_pdos, &p.tx_pdos}) {
    for (const profile::PdoSpec& pdo : *list) {
      if (!d.find(pdo.index)) continue;  // SII-only PDO
      ASSERT_EQ(value_of(s, pdo.index, 0), pdo.entries.size()) << std::hex << pdo.index;
      for (std::size_t i = 0; i < pdo.entries.size(); ++i) {
        const auto& e = pdo.entries[i];
        const std::uint32_t expected = static_cast<std::uint32_t>(e.index) << 16 |
                                       static_cast<std::uint32_t>(e.subindex) << 8 | e.bit_length;
        EXPECT_EQ(value_of(s, pdo.index, static_cast<std::uint8_t>(i + 1)), expected)
            << std::hex << pdo.index << " entry " << i + 1;
      }
    }
  }
  for (const auto& [assign, sm] : {std::pair<std::uint16_t, int>{0x1C12, 2}, {0x1C13, 3}}) {
    if (!d.find(assign)) continue;
    std::uint32_t count = 0;
    for (const auto* list : {&p.rx_pdos, &p.tx_pdos})
      for (const profile::PdoSpec& pdo : *list)
        if (pdo.sync_manager == sm) {
          ++count;
          EXPECT_EQ(value_of(s, assign, static_cast<std::uint8_t>(count)), pdo.index) << std::hex << assign;
        }
    EXPECT_EQ(value_of(s, assign, 0), count) << std::hex << assign;
  }
}

// 1C00h answers the SII's SyncManager kinds (1 mailbox out, 2 mailbox in, 3 outputs, 4 inputs).
TEST_P(DefaultPdo, SmCommunicationTypesEqualTheSiiSyncManagers) {
  const profile::ProductProfile p = profile::load_profile(GetParam());
  const Dictionary d = Dictionary::load(p);
  const ObjectStore s(d);
  ASSERT_NE(d.find(0x1C00), nullptr);
  ASSERT_EQ(value_of(s, 0x1C00, 0), p.sync_managers.size());
  for (std::size_t n = 0; n < p.sync_managers.size(); ++n)
    EXPECT_EQ(value_of(s, 0x1C00, static_cast<std::uint8_t>(n + 1)),
              static_cast<std::uint32_t>(p.sync_managers[n].kind));
}

INSTANTIATE_TEST_SUITE_P(Products, DefaultPdo, ::testing::Values("a6b", "ds5c1", "ds1000a"));

// What the manual's table prints is kept: the A6B's 1600h defaults come from its default mapping
// table (L7312+), not from the profile, and are flagged as manual values (not synthesized).
TEST(DefaultPdoSources, ManualTableValuesAreKeptAndFilledValuesAreFlagged) {
  const Dictionary a6b = Dictionary::load(profile::load_profile("a6b"));
  EXPECT_FALSE(a6b.find(0x1600, 1)->synthesized);
  const Dictionary ds5c1 = Dictionary::load(profile::load_profile("ds5c1"));
  EXPECT_TRUE(ds5c1.find(0x1600, 1)->synthesized);   // the DS5C1 table gives no default mapping
  const Dictionary ds1000a = Dictionary::load(profile::load_profile("ds1000a"));
  EXPECT_TRUE(ds1000a.find(0x1C00, 0)->synthesized);  // the DS1000A-EC table has no 1C00h
}

}  // namespace
}  // namespace vdrive::od
