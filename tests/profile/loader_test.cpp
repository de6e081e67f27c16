// Product profiles: every product loads with the values its manual gives, and a bad profile
// produces a message naming the file, the line and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "tests/profile/profile_text_edit.hpp"
#include "vdrive/profile/embedded_profiles.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
namespace {

namespace fs = std::filesystem;

using test::line_of;
using test::replace_once;

std::string embedded_text(std::string_view id) { return test::embedded_texts(id).profile; }

// A profile directory in the temp dir holding one product file.
class TempProfileDir {
public:
  TempProfileDir(const std::string& id, const std::string& text) {
    dir_ = fs::temp_directory_path() /
           ("vdrive_profile_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / id);
    std::ofstream(dir_ / id / "profile.yaml") << text;
    // A product is three files: the alarm table and motor catalogue come from the built-in copy.
    for (const auto& e : embedded_profiles()) {
      if (e.id != id) continue;
      std::ofstream(dir_ / id / "alarms.yaml") << e.alarms_yaml;
      std::ofstream(dir_ / id / "motors.yaml") << e.motors_yaml;
    }
  }
  ~TempProfileDir() { fs::remove_all(dir_); }
  std::string path() const { return dir_.string(); }
  std::string file(const std::string& id) const { return (dir_ / id / "profile.yaml").string(); }

private:
  fs::path dir_;
};

// Loads `text` as product `id` from a temp dir and returns the error message ("" if none).
std::string load_error(const std::string& id, const std::string& text, std::string* file = nullptr) {
  TempProfileDir dir(id, text);
  if (file) *file = dir.file(id);
  try {
    load_profile(id, dir.path());
  } catch (const ProfileError& e) {
    return e.what();
  }
  return {};
}

TEST(ProfileLoader, KnowsTheThreeProducts) {
  EXPECT_EQ(known_products(), (std::vector<std::string>{"a6b", "ds1000a", "ds5c1"}));
}

TEST(ProfileLoader, A6bHasTheManualsIdentityAndSiiWords) {
  const ProductProfile p = load_profile("a6b");
  EXPECT_EQ(p.id, "a6b");
  EXPECT_EQ(p.identity.vendor_id, 0x0000066Fu);       // L6650
  EXPECT_EQ(p.identity.device_type, 0x00020192u);     // L6498
  EXPECT_EQ(p.identity.product_code >> 28, 6u);       // bits 31-28 = 6 for A6B, L6662-L6664
  EXPECT_EQ(p.identity.device_name, "MADLN15BE");
  EXPECT_EQ(p.esc.pdi_control, 0x0C05);
  EXPECT_EQ(p.esc.pdi_config, 0x6603);
  EXPECT_EQ(p.esc.sync_pulse_length, 0x0064);
  EXPECT_EQ(p.esc.features, 0x018C);
  EXPECT_EQ(p.esc.eeprom_bytes, 2048);                // 16 kbit
  EXPECT_EQ(p.mailbox.rx_offset, 0x1000);
  EXPECT_EQ(p.mailbox.rx_size, 0x0100);
  EXPECT_EQ(p.mailbox.tx_offset, 0x1200);
  EXPECT_EQ(p.mailbox.tx_size, 0x0100);
  ASSERT_TRUE(p.mailbox.boot_rx_offset.has_value());
  EXPECT_EQ(*p.mailbox.boot_tx_offset, 0x1200);
  EXPECT_EQ(p.mailbox.protocols, 0x000C);
  EXPECT_EQ(p.mailbox_rules.sm0_min_length, 32);
  EXPECT_EQ(p.mailbox_rules.sm0_control_value, 0x06);
  EXPECT_EQ(p.mailbox_rules.sm1_control_value, 0x02);
  EXPECT_TRUE(p.has_bootstrap);
  EXPECT_EQ(p.al_codes.invalid_mailbox_config, 0x0016);
  EXPECT_EQ(p.al_codes.invalid_boot_mailbox_config, 0x0016);  // Err81.1 covers Init->Boot
  EXPECT_EQ(p.al_codes.eeprom_error, 0x0051);
  EXPECT_EQ(p.coe_details & 0x20, 0) << "A6B does not support Complete Access";
  EXPECT_EQ(p.foe_details, 0);
}

TEST(ProfileLoader, Ds5c1HasNoBootAndOnlyCoe) {
  const ProductProfile p = load_profile("ds5c1");
  EXPECT_EQ(p.identity.vendor_id, 0x00000556u);
  EXPECT_EQ(p.identity.product_code, 0x10305070u);
  EXPECT_EQ(p.identity.device_type, 0x04020192u);
  EXPECT_FALSE(p.has_bootstrap);
  EXPECT_FALSE(p.mailbox.boot_rx_offset.has_value());
  EXPECT_EQ(p.mailbox.protocols, 0x0004);
  EXPECT_EQ(p.esc.build, 0x0040);
  EXPECT_EQ(p.esc.features, 0x0184);
  EXPECT_EQ(p.mailbox_rules.sm1_min_length, 40);
  EXPECT_EQ(p.mailbox_rules.sm0_start_max, 0x10FF);
  EXPECT_EQ(p.mailbox_rules.sm1_start_min, 0x1200);
  EXPECT_EQ(p.al_codes.bootstrap_not_supported, 0x0013);
  EXPECT_EQ(p.coe_details & 0x20, 0) << "DS5C1 does not support Complete Access";
  EXPECT_FALSE(p.explicit_device_id);
}

TEST(ProfileLoader, Ds1000aHasFoeAndBoot) {
  const ProductProfile p = load_profile("ds1000a");
  EXPECT_EQ(p.identity.vendor_id, 0x00000973u);
  EXPECT_EQ(p.identity.product_code, 0x00004A39u);
  EXPECT_EQ(p.identity.revision, 1u);
  EXPECT_EQ(p.identity.device_name, "DS1000A-EC");
  EXPECT_TRUE(p.has_bootstrap);
  EXPECT_EQ(p.mailbox.protocols & 0x0008, 0x0008);  // FoE
  EXPECT_EQ(p.foe_details, 1);
}

// SM2/SM3 lengths must equal the default mapping's size, or the product itself would reject them.
TEST(ProfileLoader, ProcessDataSyncManagersMatchDefaultMappings) {
  const std::map<std::string, std::pair<int, int>> manual_sizes = {
      {"a6b", {9, 23}}, {"ds5c1", {13, 13}}, {"ds1000a", {15, 17}}};
  for (const auto& [id, sizes] : manual_sizes) {
    SCOPED_TRACE(id);
    const ProductProfile p = load_profile(id);
    ASSERT_EQ(p.sync_managers.size(), 4u);
    EXPECT_EQ(p.sync_managers[0].kind, SyncManagerSpec::Kind::MailboxOut);
    EXPECT_EQ(p.sync_managers[1].kind, SyncManagerSpec::Kind::MailboxIn);
    EXPECT_EQ(p.sync_managers[2].kind, SyncManagerSpec::Kind::Outputs);
    EXPECT_EQ(p.sync_managers[3].kind, SyncManagerSpec::Kind::Inputs);
    EXPECT_EQ(p.sync_managers[2].length, sizes.first);
    EXPECT_EQ(p.sync_managers[3].length, sizes.second);
    EXPECT_EQ(p.sync_managers[2].control, 0x64);
    EXPECT_EQ(p.sync_managers[3].control, 0x20);
    int rx_bits = 0, tx_bits = 0;
    for (const auto& e : p.rx_pdos.at(0).entries) rx_bits += e.bit_length;
    for (const auto& e : p.tx_pdos.at(0).entries) tx_bits += e.bit_length;
    EXPECT_EQ(rx_bits, 8 * sizes.first);
    EXPECT_EQ(tx_bits, 8 * sizes.second);
    // The mailbox SMs are the SII mailbox words.
    EXPECT_EQ(p.sync_managers[0].start, p.mailbox.rx_offset);
    EXPECT_EQ(p.sync_managers[0].length, p.mailbox.rx_size);
    EXPECT_EQ(p.sync_managers[1].start, p.mailbox.tx_offset);
    EXPECT_EQ(p.sync_managers[1].length, p.mailbox.tx_size);
  }
}

TEST(ProfileLoader, DirectoryCopyLoadsLikeTheEmbeddedOne) {
  const ProductProfile from_tree = load_profile("a6b", VDRIVE_PROFILE_DIR);
  const ProductProfile embedded = load_profile("a6b");
  EXPECT_EQ(from_tree.identity.product_code, embedded.identity.product_code);
  EXPECT_EQ(from_tree.sync_managers.size(), embedded.sync_managers.size());
  EXPECT_EQ(embedded_text("a6b").size(), fs::file_size(fs::path(VDRIVE_PROFILE_DIR) / "a6b" / "profile.yaml"));
}

TEST(ProfileLoader, UnknownProductListsTheKnownOnes) {
  try {
    load_profile("a7b");
    FAIL() << "no error";
  } catch (const ProfileError& e) {
    EXPECT_STREQ(e.what(), "unknown product 'a7b' (known products: a6b, ds1000a, ds5c1)");
  }
}

TEST(ProfileLoader, UnknownProductInDirectoryNamesTheFile) {
  TempProfileDir dir("a6b", embedded_text("a6b"));
  try {
    load_profile("zz9", dir.path());
    FAIL() << "no error";
  } catch (const ProfileError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("unknown product 'zz9'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(dir.path() + "/zz9/profile.yaml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a6b, ds1000a, ds5c1"), std::string::npos) << msg;
  }
}

TEST(ProfileLoader, IdThatIsAPathIsRejected) {
  TempProfileDir dir("a6b", embedded_text("a6b"));
  EXPECT_THROW(load_profile("../a6b", dir.path()), ProfileError);
  EXPECT_THROW(load_profile("", dir.path()), ProfileError);
}

TEST(ProfileLoader, WrongTypeNamesFileLineAndField) {
  const std::string text = replace_once(embedded_text("a6b"), "vendor_id: 0x0000066F", "vendor_id: -5");
  std::string file;
  const std::string msg = load_error("a6b", text, &file);
  EXPECT_EQ(msg, file + ":" + std::to_string(line_of(text, "vendor_id: -5")) +
                     ": identity.vendor_id: expected an unsigned 32-bit integer");
}

TEST(ProfileLoader, OutOfRangeValueIsAnError) {
  const std::string text = replace_once(embedded_text("ds5c1"), "fmmu_count: 3", "fmmu_count: 0x100");
  std::string file;
  const std::string msg = load_error("ds5c1", text, &file);
  EXPECT_EQ(msg, file + ":" + std::to_string(line_of(text, "fmmu_count: 0x100")) +
                     ": esc.fmmu_count: expected an unsigned 8-bit integer");
}

TEST(ProfileLoader, MisspeltKeyIsReportedAsTheMissingField) {
  const std::string text = replace_once(embedded_text("a6b"), "  revision: 0x00010000", "  revison: 0x00010000");
  std::string file;
  const std::string msg = load_error("a6b", text, &file);
  EXPECT_EQ(msg, file + ":" + std::to_string(line_of(text, "identity:")) + ": identity.revision: missing");
}

TEST(ProfileLoader, ExtraKeyIsAnError) {
  const std::string text = replace_once(embedded_text("a6b"), "has_bootstrap: true", "has_bootstrap: true\nhas_boot: 1");
  std::string file;
  const std::string msg = load_error("a6b", text, &file);
  EXPECT_EQ(msg, file + ":" + std::to_string(line_of(text, "has_boot: 1")) + ": has_boot: unknown field");
}

TEST(ProfileLoader, MissingFieldIsAnError) {
  const std::string text = replace_once(embedded_text("ds1000a"), "  eeprom_error: 0x0051\n", "");
  const std::string msg = load_error("ds1000a", text);
  EXPECT_NE(msg.find("al_codes.eeprom_error: missing"), std::string::npos) << msg;
}

TEST(ProfileLoader, BadEnumAndBoolAreErrors) {
  std::string msg = load_error("a6b", replace_once(embedded_text("a6b"), "kind: outputs", "kind: output"));
  EXPECT_NE(msg.find("sync_managers[2].kind: expected one of mailbox_out, mailbox_in, outputs, inputs"),
            std::string::npos)
      << msg;
  msg = load_error("a6b", replace_once(embedded_text("a6b"), "require_even_start: true", "require_even_start: yes"));
  EXPECT_NE(msg.find("mailbox_rules.require_even_start: expected true or false"), std::string::npos) << msg;
}

TEST(ProfileLoader, PdoEntryTypeMustMatchBitLength) {
  const std::string msg = load_error(
      "a6b", replace_once(embedded_text("a6b"), "bits: 16, type: UNSIGNED16, name: Controlword",
                          "bits: 32, type: UNSIGNED16, name: Controlword"));
  EXPECT_NE(msg.find("rx_pdos[0].entries[0].bits: UNSIGNED16 is 16 bits, not 32"), std::string::npos) << msg;
}

TEST(ProfileLoader, IdMustMatchDirectory) {
  const std::string msg = load_error("a6b", replace_once(embedded_text("a6b"), "id: a6b", "id: a6c"));
  EXPECT_NE(msg.find("id: is 'a6c', expected 'a6b'"), std::string::npos) << msg;
}

TEST(ProfileLoader, YamlSyntaxErrorNamesTheLine) {
  const std::string text = replace_once(embedded_text("a6b"), "title: Panasonic MINAS-A6B", "title: [unclosed");
  std::string file;
  const std::string msg = load_error("a6b", text, &file);
  EXPECT_EQ(msg.rfind(file + ":", 0), 0u) << msg;
  EXPECT_NE(msg.find("YAML syntax error"), std::string::npos) << msg;
}

TEST(ProfileLoader, EmptyOrNonMappingFileIsAnError) {
  std::string file;
  std::string msg = load_error("a6b", "", &file);
  EXPECT_EQ(msg.rfind(file, 0), 0u) << msg;
  EXPECT_NE(msg.find("(top level): expected a mapping"), std::string::npos) << msg;
  msg = load_error("a6b", "- id: a6b\n", &file);
  EXPECT_EQ(msg, file + ":1: (top level): expected a mapping");
  msg = load_error("a6b", "id: a6b\nid: a6b\n", &file);
  EXPECT_EQ(msg, file + ":2: id: duplicate key");
}

TEST(ProfileLoader, BootstrapNeedsABootMailbox) {
  std::string text = embedded_text("ds5c1");
  text = replace_once(text, "has_bootstrap: false", "has_bootstrap: true");
  const std::string msg = load_error("ds5c1", text);
  EXPECT_NE(msg.find("has_bootstrap: is true but mailbox has no boot_* mailbox"), std::string::npos) << msg;
}

TEST(ProfileLoader, CompleteAccessAbortIsRequiredAndAnSdoAbortCode) {
  std::string file;
  std::string text = replace_once(embedded_text("a6b"), "complete_access_abort: 0x06010000\n", "");
  std::string msg = load_error("a6b", text, &file);
  EXPECT_EQ(msg.rfind(file + ":", 0), 0u) << msg;
  EXPECT_NE(msg.find(": complete_access_abort: missing"), std::string::npos) << msg;
  text = replace_once(embedded_text("ds5c1"), "complete_access_abort: 0x06010004", "complete_access_abort: 0x1234");
  msg = load_error("ds5c1", text, &file);
  EXPECT_EQ(msg, file + ":" + std::to_string(line_of(text, "complete_access_abort: 0x1234")) +
                     ": complete_access_abort: expected an SDO abort code (0x05xxxxxx-0x08xxxxxx)");
}

}  // namespace
}  // namespace vdrive::profile
