// ESI export: the XML is parsed back with tinyxml2 and compared with the profile and dictionary it
// was built from (identity, SyncManagers, PDOs, mailbox, DC, EEPROM, object count).
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "vdrive/esi/esi_dictionary.hpp"
#include "vdrive/esi/esi_export.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace {

using namespace vdrive;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

// ESI numbers: "#x1A2B" (hex) or decimal.
std::uint64_t number(const char* text) {
  EXPECT_NE(text, nullptr);
  if (text == nullptr) return 0;
  const std::string s(text);
  if (s.rfind("#x", 0) == 0) return std::stoull(s.substr(2), nullptr, 16);
  return std::stoull(s, nullptr, 10);
}

std::string text_of(const XMLElement* e, const char* child) {
  const XMLElement* c = e ? e->FirstChildElement(child) : nullptr;
  return c && c->GetText() ? c->GetText() : "";
}

std::vector<const XMLElement*> children(const XMLElement* parent, const char* name) {
  std::vector<const XMLElement*> out;
  for (const XMLElement* e = parent ? parent->FirstChildElement(name) : nullptr; e; e = e->NextSiblingElement(name))
    out.push_back(e);
  return out;
}

std::vector<std::uint8_t> hex_bytes(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return out;
}

class EsiExport : public ::testing::TestWithParam<std::string> {
protected:
  void SetUp() override {
    profile_ = profile::load_profile(GetParam());
    dict_ = od::shared_dictionary(profile_);
  }

  // Exports and parses; `device` is the one <Device>.
  void export_and_parse(const esi::EsiOptions& options = {}) {
    xml_ = esi::export_esi(profile_, *dict_, options);
    ASSERT_EQ(doc_.Parse(xml_.c_str(), xml_.size()), tinyxml2::XML_SUCCESS) << doc_.ErrorStr();
    root_ = doc_.RootElement();
    ASSERT_NE(root_, nullptr);
    device_ = root_->FirstChildElement("Descriptions")->FirstChildElement("Devices")->FirstChildElement("Device");
    ASSERT_NE(device_, nullptr);
  }

  profile::ProductProfile profile_;
  std::shared_ptr<const od::Dictionary> dict_;
  std::string xml_;
  XMLDocument doc_;
  const XMLElement* root_ = nullptr;
  const XMLElement* device_ = nullptr;
};

TEST_P(EsiExport, IdentityIsTheProfiles) {
  export_and_parse();
  EXPECT_STREQ(root_->Name(), "EtherCATInfo");
  const XMLElement* vendor = root_->FirstChildElement("Vendor");
  EXPECT_EQ(number(vendor->FirstChildElement("Id")->GetText()), profile_.identity.vendor_id);
  EXPECT_EQ(text_of(vendor, "Name"), profile_.identity.vendor_name);
  const XMLElement* type = device_->FirstChildElement("Type");
  EXPECT_EQ(number(type->Attribute("ProductCode")), profile_.identity.product_code);
  EXPECT_EQ(number(type->Attribute("RevisionNo")), profile_.identity.revision);
  EXPECT_EQ(std::string(type->GetText()), profile_.identity.order_code);
  EXPECT_EQ(text_of(device_, "Name"), profile_.identity.device_name);
  EXPECT_EQ(text_of(device_, "GroupType"), profile_.identity.group);
  const XMLElement* group = root_->FirstChildElement("Descriptions")->FirstChildElement("Groups")->FirstChildElement("Group");
  EXPECT_EQ(text_of(group, "Type"), profile_.identity.group);
  // 1000h low word is the CiA profile: every product here is a CiA 402 drive.
  EXPECT_EQ(text_of(device_->FirstChildElement("Profile"), "ProfileNo"), "402");
}

TEST_P(EsiExport, SyncManagersAreTheProfiles) {
  export_and_parse();
  const auto sms = children(device_, "Sm");
  ASSERT_EQ(sms.size(), profile_.sync_managers.size());
  const char* names[] = {"", "MBoxOut", "MBoxIn", "Outputs", "Inputs"};
  for (std::size_t i = 0; i < sms.size(); ++i) {
    const auto& spec = profile_.sync_managers[i];
    SCOPED_TRACE(i);
    EXPECT_EQ(number(sms[i]->Attribute("StartAddress")), spec.start);
    EXPECT_EQ(number(sms[i]->Attribute("DefaultSize")), spec.length);
    EXPECT_EQ(number(sms[i]->Attribute("ControlByte")), spec.control);
    EXPECT_EQ(number(sms[i]->Attribute("Enable")), spec.enable ? 1u : 0u);
    EXPECT_STREQ(sms[i]->GetText(), names[static_cast<int>(spec.kind)]);
  }
  // The mailbox SMs carry the minimum length the firmware checks at Init->PreOp.
  EXPECT_EQ(number(sms[0]->Attribute("MinSize")), profile_.mailbox_rules.sm0_min_length);
  EXPECT_EQ(number(sms[1]->Attribute("MinSize")), profile_.mailbox_rules.sm1_min_length);
  // FMMUs: outputs, inputs, mailbox state, as in the SII FMMU category.
  const auto fmmus = children(device_, "Fmmu");
  ASSERT_EQ(fmmus.size(), std::min<std::size_t>(profile_.esc.fmmu_count, 3));
  EXPECT_STREQ(fmmus[0]->GetText(), "Outputs");
  EXPECT_STREQ(fmmus[1]->GetText(), "Inputs");
}

void expect_pdos(const std::vector<const XMLElement*>& xml, const std::vector<profile::PdoSpec>& specs) {
  std::vector<const XMLElement*> assigned;
  for (const XMLElement* e : xml)
    if (e->Attribute("Sm")) assigned.push_back(e);
  ASSERT_EQ(assigned.size(), specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    SCOPED_TRACE(specs[i].index);
    EXPECT_EQ(number(assigned[i]->FirstChildElement("Index")->GetText()), specs[i].index);
    EXPECT_EQ(number(assigned[i]->Attribute("Sm")), specs[i].sync_manager);
    EXPECT_EQ(text_of(assigned[i], "Name"), specs[i].name);
    const auto entries = children(assigned[i], "Entry");
    ASSERT_EQ(entries.size(), specs[i].entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k) {
      EXPECT_EQ(number(entries[k]->FirstChildElement("Index")->GetText()), specs[i].entries[k].index);
      EXPECT_EQ(number(entries[k]->FirstChildElement("SubIndex")->GetText()), specs[i].entries[k].subindex);
      EXPECT_EQ(number(entries[k]->FirstChildElement("BitLen")->GetText()), specs[i].entries[k].bit_length);
      EXPECT_EQ(text_of(entries[k], "Name"), specs[i].entries[k].name);
      EXPECT_FALSE(text_of(entries[k], "DataType").empty());
    }
  }
}

TEST_P(EsiExport, DefaultPdosAreTheProfiles) {
  export_and_parse();
  expect_pdos(children(device_, "RxPdo"), profile_.rx_pdos);
  expect_pdos(children(device_, "TxPdo"), profile_.tx_pdos);
  // Every mapping object the product has is offered, assigned by default or not.
  auto offered = [](const std::vector<profile::PdoSpec>& defaults, const std::vector<profile::PdoObjectRule>& all) {
    std::set<std::uint16_t> indexes;
    for (const auto& d : defaults) indexes.insert(d.index);
    for (const auto& r : all) indexes.insert(r.index);
    return indexes.size();
  };
  EXPECT_EQ(children(device_, "RxPdo").size(), offered(profile_.rx_pdos, profile_.pdo_rules.rx_objects));
  EXPECT_EQ(children(device_, "TxPdo").size(), offered(profile_.tx_pdos, profile_.pdo_rules.tx_objects));
}

TEST_P(EsiExport, MailboxAdvertisesWhatTheProductSupports) {
  export_and_parse();
  const XMLElement* coe = device_->FirstChildElement("Mailbox")->FirstChildElement("CoE");
  ASSERT_NE(coe, nullptr);
  EXPECT_EQ(coe->BoolAttribute("SdoInfo"), (profile_.coe_details & 0x02) != 0);
  EXPECT_EQ(coe->BoolAttribute("PdoAssign"), (profile_.coe_details & 0x04) != 0);
  EXPECT_EQ(coe->BoolAttribute("PdoConfig"), (profile_.coe_details & 0x08) != 0);
  // Complete access is claimed only by a product that has it (SOEM would use it otherwise).
  EXPECT_EQ(coe->Attribute("CompleteAccess") != nullptr, (profile_.coe_details & 0x20) != 0);
  EXPECT_EQ(device_->FirstChildElement("Mailbox")->FirstChildElement("FoE") != nullptr, profile_.foe_details != 0);
}

TEST_P(EsiExport, DcOpModesFollowTheSyncModes) {
  export_and_parse();
  const XMLElement* dc = device_->FirstChildElement("Dc");
  const auto& s = profile_.sync;
  const std::size_t expected = s.free_run + s.sm2_event + s.dc_sync0 + s.dc_sync1;
  if (expected == 0) {
    EXPECT_EQ(dc, nullptr);
    return;
  }
  const auto modes = children(dc, "OpMode");
  ASSERT_EQ(modes.size(), expected);
  std::size_t with_sync0 = 0;
  for (const XMLElement* m : modes) {
    const std::uint64_t aa = number(m->FirstChildElement("AssignActivate")->GetText());
    EXPECT_TRUE(aa == 0x0000 || aa == 0x0300 || aa == 0x0700) << aa;
    if (aa == 0x0300) ++with_sync0;
  }
  EXPECT_EQ(with_sync0, s.dc_sync0 ? 1u : 0u);
}

TEST_P(EsiExport, EepromConfigDataIsSiiWords0To6) {
  export_and_parse();
  const XMLElement* eeprom = device_->FirstChildElement("Eeprom");
  EXPECT_EQ(number(eeprom->FirstChildElement("ByteSize")->GetText()), profile_.esc.eeprom_bytes);
  const std::vector<std::uint8_t> config = hex_bytes(text_of(eeprom, "ConfigData"));
  ASSERT_EQ(config.size(), 14u);
  auto word = [&](int w) { return static_cast<std::uint16_t>(config[2 * w] | (config[2 * w + 1] << 8)); };
  EXPECT_EQ(word(0), profile_.esc.pdi_control);
  EXPECT_EQ(word(1), profile_.esc.pdi_config);
  EXPECT_EQ(word(2), profile_.esc.sync_pulse_length);
  EXPECT_EQ(word(3), profile_.esc.extended_pdi_config);
  EXPECT_EQ(word(4), profile_.esc.station_alias);
  EXPECT_EQ(word(5), 0);
  EXPECT_EQ(word(6), 0);
  const std::string boot = text_of(eeprom, "BootStrap");
  if (profile_.has_bootstrap && profile_.mailbox.boot_rx_offset) {
    const std::vector<std::uint8_t> b = hex_bytes(boot);
    ASSERT_EQ(b.size(), 8u);
    EXPECT_EQ(b[0] | (b[1] << 8), *profile_.mailbox.boot_rx_offset);
    EXPECT_EQ(b[2] | (b[3] << 8), *profile_.mailbox.boot_rx_size);
    EXPECT_EQ(b[4] | (b[5] << 8), *profile_.mailbox.boot_tx_offset);
    EXPECT_EQ(b[6] | (b[7] << 8), *profile_.mailbox.boot_tx_size);
  } else {
    EXPECT_TRUE(boot.empty());
  }
}

TEST_P(EsiExport, EepromImageVariantHoldsTheWholeSiiImage) {
  esi::EsiOptions options;
  options.eeprom_image = true;
  export_and_parse(options);
  const XMLElement* eeprom = device_->FirstChildElement("Eeprom");
  EXPECT_EQ(eeprom->FirstChildElement("ConfigData"), nullptr);
  EXPECT_EQ(hex_bytes(text_of(eeprom, "Data")), profile::build_sii_image(profile_));
}

TEST_P(EsiExport, DictionaryHoldsEveryObject) {
  export_and_parse();
  const XMLElement* dictionary = device_->FirstChildElement("Profile")->FirstChildElement("Dictionary");
  std::size_t with_entries = 0;
  for (const auto& o : dict_->objects()) with_entries += o.entries.empty() ? 0 : 1;
  if (with_entries == 0) {  // the object-dictionary engine has not loaded anything
    EXPECT_EQ(dictionary, nullptr);
    return;
  }
  ASSERT_NE(dictionary, nullptr);
  const auto objects = children(dictionary->FirstChildElement("Objects"), "Object");
  ASSERT_EQ(objects.size(), with_entries);
  std::size_t i = 0;
  for (const auto& o : dict_->objects()) {
    if (o.entries.empty()) continue;
    SCOPED_TRACE(o.index);
    const XMLElement* x = objects[i++];
    EXPECT_EQ(number(x->FirstChildElement("Index")->GetText()), o.index);
    EXPECT_EQ(text_of(x, "Name"), o.name);
    if (o.code == od::ObjectCode::Var) {
      EXPECT_EQ(number(x->FirstChildElement("BitSize")->GetText()), o.entries[0].bit_length);
      const XMLElement* flags = x->FirstChildElement("Flags");
      const std::string mapping = text_of(flags, "PdoMapping");
      EXPECT_EQ(mapping.find('R') != std::string::npos, (o.entries[0].access & od::access::kRxPdoMappable) != 0);
      EXPECT_EQ(mapping.find('T') != std::string::npos, (o.entries[0].access & od::access::kTxPdoMappable) != 0);
      const std::string access = text_of(flags, "Access");
      if (o.entries[0].access & od::access::kWriteAll) {
        EXPECT_TRUE(access == "rw" || access == "wo") << access;
      } else if (o.entries[0].access & od::access::kReadAll) {
        EXPECT_EQ(access, "ro");
      }
    } else {
      // A complex object names its DTxxxx type, which lists one SubItem per entry.
      const std::string type = text_of(x, "Type");
      const XMLElement* dt = nullptr;
      for (const XMLElement* d : children(dictionary->FirstChildElement("DataTypes"), "DataType"))
        if (text_of(d, "Name") == type) dt = d;
      ASSERT_NE(dt, nullptr) << type;
      const auto subs = children(dt, "SubItem");
      // An ARRAY the ETG way: subindex 0 and "Elements" of a DTxxxxARR type with ArrayInfo.
      if (subs.size() == 2 && text_of(subs[1], "Name") == "Elements") {
        EXPECT_EQ(o.code, od::ObjectCode::Array);
        const XMLElement* arr = nullptr;
        for (const XMLElement* d : children(dictionary->FirstChildElement("DataTypes"), "DataType"))
          if (text_of(d, "Name") == text_of(subs[1], "Type")) arr = d;
        ASSERT_NE(arr, nullptr);
        EXPECT_EQ(number(text_of(arr->FirstChildElement("ArrayInfo"), "Elements").c_str()), o.entries.size() - 1);
      } else {
        ASSERT_EQ(subs.size(), o.entries.size());
        for (std::size_t k = 0; k < subs.size(); ++k)
          EXPECT_EQ(number(subs[k]->FirstChildElement("SubIdx")->GetText()), o.entries[k].subindex);
      }
      EXPECT_EQ(children(x->FirstChildElement("Info"), "SubItem").size(), o.entries.size());
    }
  }
}

// The ETG schema keys SubItems by Name within a DataType and Objects' types by DataType Name:
// names must be unique (manuals repeat "For manufacturer's use" in one record) and every
// referenced type declared.
TEST_P(EsiExport, DataTypeNamesAndSubItemNamesAreUnique) {
  export_and_parse();
  const XMLElement* dictionary = device_->FirstChildElement("Profile")->FirstChildElement("Dictionary");
  if (dictionary == nullptr) GTEST_SKIP() << "empty dictionary";
  std::set<std::string> types;
  for (const XMLElement* dt : children(dictionary->FirstChildElement("DataTypes"), "DataType")) {
    EXPECT_TRUE(types.insert(text_of(dt, "Name")).second) << text_of(dt, "Name");
    std::set<std::string> subs;
    for (const XMLElement* s : children(dt, "SubItem")) EXPECT_TRUE(subs.insert(text_of(s, "Name")).second) << text_of(s, "Name");
  }
  for (const XMLElement* o : children(dictionary->FirstChildElement("Objects"), "Object"))
    EXPECT_TRUE(types.count(text_of(o, "Type"))) << text_of(o, "Type");
}

TEST_P(EsiExport, WithoutOdVariantHasNoDictionaryButTheSameDevice) {
  esi::EsiOptions options;
  options.with_dictionary = false;
  export_and_parse(options);
  EXPECT_EQ(device_->FirstChildElement("Profile")->FirstChildElement("Dictionary"), nullptr);
  EXPECT_EQ(children(device_, "Sm").size(), profile_.sync_managers.size());
  EXPECT_NE(device_->FirstChildElement("Mailbox"), nullptr);
  EXPECT_NE(device_->FirstChildElement("Eeprom"), nullptr);
}

TEST_P(EsiExport, IsDeterministic) {
  EXPECT_EQ(esi::export_esi(profile_, *dict_), esi::export_esi(profile_, *dict_));
}

INSTANTIATE_TEST_SUITE_P(Products, EsiExport, ::testing::Values("a6b", "ds5c1", "ds1000a"));

TEST(EsiExportEscaping, MarkupInNamesRoundTrips) {
  profile::ProductProfile p = profile::load_profile("ds5c1");
  p.identity.device_name = "A<B> & \"C\" 'D'";
  p.identity.vendor_name = "X&Y <Z>";
  // Its own dictionary: the shared one of ds5c1 must keep the product's identity for other tests.
  const auto dict = std::make_shared<const od::Dictionary>(od::Dictionary::load(p));
  const std::string xml = esi::export_esi(p, *dict);
  XMLDocument doc;
  ASSERT_EQ(doc.Parse(xml.c_str(), xml.size()), tinyxml2::XML_SUCCESS) << doc.ErrorStr();
  const XMLElement* root = doc.RootElement();
  EXPECT_STREQ(root->FirstChildElement("Vendor")->FirstChildElement("Name")->GetText(), "X&Y <Z>");
  const XMLElement* device = root->FirstChildElement("Descriptions")->FirstChildElement("Devices")->FirstChildElement("Device");
  EXPECT_STREQ(device->FirstChildElement("Name")->GetText(), "A<B> & \"C\" 'D'");
}

}  // namespace

namespace {

// ETG.2000 Access element: ro/rw/wo, with the states as restriction attributes when not all.
TEST(EsiAccessText, StatesBecomeRestrictions) {
  using namespace vdrive::od::access;
  EXPECT_EQ(vdrive::esi::access_text(kReadAll).access, "ro");
  EXPECT_EQ(vdrive::esi::access_text(kReadAll).read_restrictions, "");
  const auto rw = vdrive::esi::access_text(kReadAll | kWriteAll);
  EXPECT_EQ(rw.access, "rw");
  EXPECT_EQ(rw.write_restrictions, "");
  const auto preop = vdrive::esi::access_text(kReadAll | kWritePreOp);
  EXPECT_EQ(preop.access, "rw");
  EXPECT_EQ(preop.write_restrictions, "PreOP");
  EXPECT_EQ(vdrive::esi::access_text(kReadAll | kWritePreOp | kWriteSafeOp).write_restrictions, "PreOP_SafeOP");
  EXPECT_EQ(vdrive::esi::access_text(kReadAll | kWriteSafeOp | kWriteOp).write_restrictions, "SafeOP_OP");
  const auto wo = vdrive::esi::access_text(kWriteAll);
  EXPECT_EQ(wo.access, "wo");
  EXPECT_EQ(vdrive::esi::access_text(kReadOp).read_restrictions, "OP");
  // No documented access (the manual prints "-"): no Access element at all.
  EXPECT_EQ(vdrive::esi::access_text(0).access, "");
  EXPECT_EQ(vdrive::esi::pdo_mapping_text(kRxPdoMappable), "R");
  EXPECT_EQ(vdrive::esi::pdo_mapping_text(kTxPdoMappable), "T");
  EXPECT_EQ(vdrive::esi::pdo_mapping_text(kRxPdoMappable | kTxPdoMappable), "RT");
  EXPECT_EQ(vdrive::esi::pdo_mapping_text(kReadAll), "");
}

}  // namespace
