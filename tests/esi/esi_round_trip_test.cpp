// ESI round trip: each built-in product exported with `vdrive esi` (esi::export_esi) and imported
// back (esi::import_device) is the same slave: identity, SII image, object dictionary and default
// PDO mapping. The differences that remain are the ones docs/esi.md documents: the A6B's SII
// mailbox protocol word (CoE + FoE in its SII, CoE only in its ESI) and the serial number (per
// unit, not in an ESI).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ethercat/little_endian.hpp"
#include "ethercat/sii.hpp"
#include "vdrive/esi/esi_export.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/esi/esi_reader.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace {

using namespace vdrive;

class EsiRoundTrip : public ::testing::TestWithParam<std::string> {
protected:
  void SetUp() override {
    builtin_ = profile::load_profile(GetParam());
    // Its own copy: other tests of this binary change identities of cached dictionaries.
    dictionary_ = std::make_shared<const od::Dictionary>(od::Dictionary::load(builtin_));
  }

  esi::ImportedDevice round_trip(const esi::EsiOptions& options = {}) {
    const std::string xml = esi::export_esi(builtin_, *dictionary_, options);
    const std::vector<esi::EsiDevice> devices = esi::parse_esi(xml, GetParam() + ".xml");
    EXPECT_EQ(devices.size(), 1u);
    return esi::import_device(devices.at(0));
  }

  profile::ProductProfile builtin_;
  std::shared_ptr<const od::Dictionary> dictionary_;
};

TEST_P(EsiRoundTrip, IdentityComesBack) {
  const profile::Identity& a = builtin_.identity;
  const profile::Identity& b = round_trip().profile.identity;
  EXPECT_EQ(b.vendor_id, a.vendor_id);
  EXPECT_EQ(b.product_code, a.product_code);
  EXPECT_EQ(b.revision, a.revision);
  EXPECT_EQ(b.device_type, a.device_type);
  EXPECT_EQ(b.device_name, a.device_name);
  EXPECT_EQ(b.hardware_version, a.hardware_version);
  EXPECT_EQ(b.software_version, a.software_version);
  EXPECT_EQ(b.vendor_name, a.vendor_name);
  EXPECT_EQ(b.order_code, a.order_code);
  EXPECT_EQ(b.group, a.group);
}

TEST_P(EsiRoundTrip, SiiImageIsTheSameButTheA6bProtocolWord) {
  const std::vector<std::uint8_t> expected = profile::build_sii_image(builtin_);
  std::vector<std::uint8_t> imported = round_trip().sii_image;
  ASSERT_EQ(imported.size(), expected.size());
  // The serial number is per unit; an ESI has none (the import's is 0).
  for (std::size_t i = 2 * ecat::sii::kWordSerial; i < 2 * ecat::sii::kWordSerial + 4; ++i) {
    EXPECT_EQ(imported[i], 0) << i;
    imported[i] = expected[i];
  }
  constexpr std::size_t kProtocols = 2 * ecat::sii::kWordMailboxProtocols;
  if (builtin_.mailbox.protocols != ecat::sii::mailbox_protocol::kCoE && builtin_.foe_details == 0) {
    // The A6B: its SII announces FoE (L3827-L3831), its ESI lists the CoE it supports (docs/esi.md).
    EXPECT_EQ(imported[kProtocols] | imported[kProtocols + 1] << 8, ecat::sii::mailbox_protocol::kCoE);
    imported[kProtocols] = expected[kProtocols];
    imported[kProtocols + 1] = expected[kProtocols + 1];
  }
  for (std::size_t i = 0; i < expected.size(); ++i)
    ASSERT_EQ(imported[i], expected[i]) << "SII byte 0x" << std::hex << i << " (word 0x" << i / 2 << ")";
}

TEST_P(EsiRoundTrip, SiiImageFromEepromDataIsExact) {
  esi::EsiOptions options;
  options.eeprom_image = true;
  EXPECT_EQ(round_trip(options).sii_image, profile::build_sii_image(builtin_));
}

TEST_P(EsiRoundTrip, ObjectDictionaryComesBackEntryForEntry) {
  const esi::ImportedDevice imported = round_trip();
  const od::Dictionary& b = *imported.dictionary;
  std::size_t compared = 0;
  for (const od::ObjectDesc& x : dictionary_->objects()) {
    if (x.entries.empty()) continue;  // nothing a master could address: not exported
    const od::ObjectDesc* y = b.find(x.index);
    ASSERT_NE(y, nullptr) << std::hex << x.index;
    EXPECT_EQ(y->name, x.name) << std::hex << x.index;
    EXPECT_EQ(y->code, x.code) << std::hex << x.index;
    ASSERT_EQ(y->entries.size(), x.entries.size()) << std::hex << x.index;
    for (std::size_t i = 0; i < x.entries.size(); ++i) {
      const od::EntryDesc& e = x.entries[i];
      const od::EntryDesc& f = y->entries[i];
      const std::string at = [&] { char s[16]; std::snprintf(s, sizeof s, "%04X:%02X", e.index, e.subindex); return std::string(s); }();
      EXPECT_EQ(f.subindex, e.subindex) << at;
      EXPECT_EQ(f.name, e.name) << at;
      EXPECT_EQ(f.type, e.type) << at;
      EXPECT_EQ(f.bit_length, e.bit_length) << at;
      EXPECT_EQ(f.access, e.access) << at;
      EXPECT_EQ(f.min, e.min) << at;
      EXPECT_EQ(f.max, e.max) << at;
      // The serial number is per unit; the sync parameters 1C32h/1C33h report are the firmware's
      // power-on values, not the table's (SyncParametersAreWhatTheProductReports).
      const bool serial = e.index == 0x1018 && e.subindex == 4;
      const bool reported = (e.index == 0x1C32 || e.index == 0x1C33) &&
                            (e.subindex == 0 || e.subindex == 4 || e.subindex == 5 || e.subindex == 6 || e.subindex == 9);
      if (!serial && !reported) EXPECT_EQ(f.default_value, e.default_value) << at;
      ++compared;
    }
  }
  EXPECT_EQ(b.objects().size(), dictionary_->objects().size());
  EXPECT_GT(compared, 100u);
}

TEST_P(EsiRoundTrip, DefaultPdoMappingComesBack) {
  const profile::ProductProfile p = round_trip().profile;
  auto same = [](const std::vector<profile::PdoSpec>& a, const std::vector<profile::PdoSpec>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(b[i].index, a[i].index);
      EXPECT_EQ(b[i].name, a[i].name);
      EXPECT_EQ(b[i].sync_manager, a[i].sync_manager);
      EXPECT_EQ(b[i].fixed, a[i].fixed);
      ASSERT_EQ(b[i].entries.size(), a[i].entries.size()) << std::hex << a[i].index;
      for (std::size_t k = 0; k < a[i].entries.size(); ++k) {
        EXPECT_EQ(b[i].entries[k].index, a[i].entries[k].index);
        EXPECT_EQ(b[i].entries[k].subindex, a[i].entries[k].subindex);
        EXPECT_EQ(b[i].entries[k].bit_length, a[i].entries[k].bit_length);
        EXPECT_EQ(b[i].entries[k].data_type, a[i].entries[k].data_type);
        EXPECT_EQ(b[i].entries[k].name, a[i].entries[k].name);
      }
    }
  };
  same(builtin_.rx_pdos, p.rx_pdos);
  same(builtin_.tx_pdos, p.tx_pdos);
  // Every mapping object of the product comes back, fixed where it is fixed.
  ASSERT_EQ(p.pdo_rules.rx_objects.size(), builtin_.pdo_rules.rx_objects.size());
  ASSERT_EQ(p.pdo_rules.tx_objects.size(), builtin_.pdo_rules.tx_objects.size());
  for (std::size_t i = 0; i < p.pdo_rules.rx_objects.size(); ++i) {
    EXPECT_EQ(p.pdo_rules.rx_objects[i].index, builtin_.pdo_rules.rx_objects[i].index);
    EXPECT_EQ(p.pdo_rules.rx_objects[i].fixed, builtin_.pdo_rules.rx_objects[i].fixed);
  }
}

// What a master reads from 1C32h/1C33h 04h-06h after power-on (the built-in firmware fills them from
// the product's sync settings) is what the ESI gives and what the imported device reports.
TEST_P(EsiRoundTrip, SyncParametersAreWhatTheProductReports) {
  const esi::ImportedDevice imported = round_trip();
  const profile::SyncSpec& a = builtin_.sync;
  const profile::SyncSpec& b = imported.profile.sync;
  for (const auto& [x, y] : {std::pair{&a.sm2, &b.sm2}, std::pair{&a.sm3, &b.sm3}}) {
    EXPECT_EQ(y->supported_sync_types, x->supported_sync_types);
    EXPECT_EQ(y->min_cycle_time_ns, x->min_cycle_time_ns);
    EXPECT_EQ(y->calc_and_copy_time_ns, x->calc_and_copy_time_ns);
    EXPECT_EQ(y->delay_time_ns, x->delay_time_ns);
  }
  if (a.sm2.min_cycle_time_ns != 0) EXPECT_EQ(b.cycle_min_ns, a.sm2.min_cycle_time_ns);
}

TEST_P(EsiRoundTrip, TheSiiImageGivesTheSerialNumber) {
  esi::EsiOptions options;
  options.eeprom_image = true;
  const esi::ImportedDevice imported = round_trip(options);
  EXPECT_EQ(imported.profile.identity.serial, builtin_.identity.serial);
  const od::EntryDesc* serial = imported.dictionary->find(0x1018, 4);
  ASSERT_NE(serial, nullptr);
  EXPECT_EQ(ecat::get_le32(serial->default_value, 0), builtin_.identity.serial);
}

TEST_P(EsiRoundTrip, ACia402DriveGetsTheGenericPersonality) {
  const profile::ProductProfile p = round_trip().profile;
  EXPECT_EQ(p.modes.supported_drive_modes, builtin_.modes.supported_drive_modes);
  EXPECT_FALSE(p.modes.modes.empty());
  EXPECT_EQ(p.drive.vendor_stop.rule, profile::VendorStopRule::None);
  EXPECT_EQ(p.drive.io_rules, profile::IoRuleSet::Generic);
  ASSERT_NE(p.find_alarm("8611h"), nullptr);
  EXPECT_EQ(p.find_alarm("8611h")->error_code, 0x8611);
}

INSTANTIATE_TEST_SUITE_P(Products, EsiRoundTrip, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
