// profile.yaml's PDO rules, modes and homing data against the object dictionary extracted
// independently from the manuals' OD tables (objects.yaml): both must tell the same story.
#include <gtest/gtest.h>

#include "vdrive/od/dictionary.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
namespace {

// The entry's factory value as an integer (little-endian bytes, sign-extended for signed types).
std::int64_t default_of(const od::EntryDesc& e) {
  std::uint64_t raw = 0;
  for (std::size_t i = 0; i < e.default_value.size() && i < 8; ++i)
    raw |= static_cast<std::uint64_t>(e.default_value[i]) << (8 * i);
  const unsigned bits = 8 * static_cast<unsigned>(std::min<std::size_t>(e.default_value.size(), 8));
  if (od::is_signed(e.type) && bits < 64 && (raw >> (bits - 1)) & 1) raw |= ~0ULL << bits;
  return static_cast<std::int64_t>(raw);
}

class ProfileOdAgreement : public ::testing::TestWithParam<std::string> {
protected:
  void SetUp() override {
    profile_ = load_profile(GetParam());
    dict_.emplace(od::Dictionary::load(profile_));
  }
  ProductProfile profile_;
  std::optional<od::Dictionary> dict_;
};

// Every 16xxh/1Axxh mapping object of the dictionary is in pdo_rules with the same entry count
// (sub 0's maximum), and 1C12h/1C13h sub 0's maximum is the assignable count.
TEST_P(ProfileOdAgreement, MappingObjectsAndAssignment) {
  std::size_t rx = 0, tx = 0;
  for (const od::ObjectDesc& o : dict_->objects()) {
    const bool is_rx = o.index >= 0x1600 && o.index <= 0x17FF, is_tx = o.index >= 0x1A00 && o.index <= 0x1BFF;
    if (!is_rx && !is_tx) continue;
    const auto& rules = is_rx ? profile_.pdo_rules.rx_objects : profile_.pdo_rules.tx_objects;
    const auto rule = std::find_if(rules.begin(), rules.end(), [&](const PdoObjectRule& r) { return r.index == o.index; });
    ASSERT_NE(rule, rules.end()) << std::hex << o.index;
    const od::EntryDesc* sub0 = o.entry(0);
    ASSERT_NE(sub0, nullptr);
    ASSERT_TRUE(sub0->max.has_value());
    EXPECT_EQ(*sub0->max, rule->max_entries) << std::hex << o.index;
    (is_rx ? rx : tx)++;
  }
  EXPECT_EQ(rx, profile_.pdo_rules.rx_objects.size());
  EXPECT_EQ(tx, profile_.pdo_rules.tx_objects.size());
  const od::EntryDesc* rx_assign = dict_->find(0x1C12, 0);
  ASSERT_NE(rx_assign, nullptr);
  ASSERT_TRUE(rx_assign->max.has_value());
  EXPECT_EQ(*rx_assign->max, profile_.pdo_rules.max_rx_assigned);
}

// 60E3h has one subindex per listed homing method.
TEST_P(ProfileOdAgreement, HomingListLength) {
  const od::ObjectDesc* list = dict_->find(0x60E3);
  ASSERT_NE(list, nullptr);
  EXPECT_EQ(list->max_subindex(), profile_.homing.listed.size());
}

// The objects and subindexes sync: names (threshold and miss-count objects, counter subindexes,
// 20h when sync_error_flag) exist in the dictionary.
TEST_P(ProfileOdAgreement, SyncObjectsExist) {
  const SyncSpec& s = profile_.sync;
  if (s.missed_sync_threshold_object != 0) {
    EXPECT_NE(dict_->find(s.missed_sync_threshold_object, 0), nullptr) << std::hex << s.missed_sync_threshold_object;
  }
  if (s.sync_error_count_object != 0) {
    EXPECT_NE(dict_->find(s.sync_error_count_object, 0), nullptr) << std::hex << s.sync_error_count_object;
  }
  for (const std::uint16_t index : {0x1C32, 0x1C33}) {
    for (const std::uint8_t sub : {s.sm_event_missed_subindex, s.cycle_too_small_subindex}) {
      if (sub != 0) {
        EXPECT_NE(dict_->find(index, sub), nullptr) << std::hex << index << ":" << int(sub);
      }
    }
    if (s.sync_error_flag) {
      EXPECT_NE(dict_->find(index, 0x20), nullptr) << std::hex << index;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Products, ProfileOdAgreement, ::testing::Values("a6b", "ds5c1", "ds1000a"));

// The DS1000-EC table gives initial values for everything (L4414-L5228): compare them.
TEST(ProfileOdAgreementDs1000a, InitialValuesMatch) {
  const ProductProfile p = load_profile("ds1000a");
  const od::Dictionary d = od::Dictionary::load(p);
  auto value = [&](std::uint16_t index, std::uint8_t sub) {
    const od::EntryDesc* e = d.find(index, sub);
    EXPECT_NE(e, nullptr) << std::hex << index << ":" << int(sub);
    return e ? default_of(*e) : -1;
  };
  EXPECT_EQ(value(0x6502, 0), p.modes.supported_drive_modes);  // L5226
  EXPECT_EQ(value(0x6060, 0), p.modes.default_mode);           // L4909
  EXPECT_EQ(value(0x6098, 0), p.homing.default_method);        // L5013
  EXPECT_EQ(value(0x1C32, 1), p.sync.sm2.default_sync_type);   // L4703
  EXPECT_EQ(value(0x1C32, 5), p.sync.sm2.min_cycle_time_ns);   // L4730
  EXPECT_EQ(value(0x1C33, 6), p.sync.sm3.calc_and_copy_time_ns);  // L4769
  for (std::size_t i = 0; i < p.homing.listed.size(); ++i)
    EXPECT_EQ(value(0x60E3, static_cast<std::uint8_t>(i + 1)), p.homing.listed[i]) << i;  // L5118-L5192
}

// The DS5C1 60E3h table gives the listed methods as values (L3445-L3491).
TEST(ProfileOdAgreementDs5c1, HomingListValuesMatch) {
  const ProductProfile p = load_profile("ds5c1");
  const od::Dictionary d = od::Dictionary::load(p);
  for (std::size_t i = 0; i < p.homing.listed.size(); ++i) {
    const od::EntryDesc* e = d.find(0x60E3, static_cast<std::uint8_t>(i + 1));
    ASSERT_NE(e, nullptr) << i;
    EXPECT_EQ(default_of(*e), p.homing.listed[i]) << i;
  }
}

}  // namespace
}  // namespace vdrive::profile
