// Dictionary::load: the dictionary equals profiles/<id>/objects.yaml (read here independently with
// yaml-cpp), identity comes from the profile, access/PDO/default/string rules, storage layout, and
// load errors that name file, line and field.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "tests/od/od_test_support.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/embedded_profiles.hpp"
#include "vdrive/profile/profile_loader.hpp"

#ifndef VDRIVE_PROFILE_DIR
#error "vdrive_core defines VDRIVE_PROFILE_DIR (the source profiles directory)"
#endif

namespace vdrive::od {
namespace {

using namespace od::test;

std::string source_file(const std::string& id) { return std::string(VDRIVE_PROFILE_DIR) + "/" + id + "/objects.yaml"; }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Index -> subindexes, as the YAML file lists them.
std::map<std::uint16_t, std::set<unsigned>> yaml_layout(const std::string& id) {
  const YAML::Node root = YAML::LoadFile(source_file(id));
  std::map<std::uint16_t, std::set<unsigned>> out;
  for (const auto& o : root["objects"]) {
    auto& subs = out[o["index"].as<std::uint16_t>()];
    for (const auto& e : o["entries"]) subs.insert(e["subindex"].as<unsigned>());
  }
  return out;
}

class OdProduct : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Products, OdProduct, ::testing::Values("a6b", "ds5c1", "ds1000a"));

TEST_P(OdProduct, EmbeddedObjectsYamlIsTheSourceFileByteForByte) {
  const std::string id = GetParam();
  const profile::EmbeddedProfile* found = nullptr;
  for (const auto& p : profile::embedded_profiles())
    if (p.id == id) found = &p;
  ASSERT_NE(found, nullptr);
  EXPECT_GT(found->objects_yaml.size(), 0u);
  for (const std::string_view piece : found->objects_yaml) EXPECT_LE(piece.size(), 60000u);
  EXPECT_EQ(profile::embedded_objects_yaml(*found), read_file(source_file(id)));
}

TEST_P(OdProduct, ObjectsAndEntriesAreTheYamlsPlusMissingIdentity) {  // and a missing 1C00h
  const std::string id = GetParam();
  const auto yaml = yaml_layout(id);
  const YAML::Node header = YAML::LoadFile(source_file(id));
  std::size_t yaml_entries = 0;
  for (const auto& [index, subs] : yaml) yaml_entries += subs.size();
  ASSERT_EQ(yaml.size(), header["object_count"].as<std::size_t>());
  ASSERT_EQ(yaml_entries, header["entry_count"].as<std::size_t>());

  // Identity objects the table lacks are added: 1000h, 1008h, 1009h, 100Ah (one entry each) and
  // 1018h:00-04.
  const std::map<std::uint16_t, std::set<unsigned>> identity = {
      {0x1000, {0}}, {0x1008, {0}}, {0x1009, {0}}, {0x100A, {0}}, {0x1018, {0, 1, 2, 3, 4}}};
  std::size_t added_objects = 0, added_entries = 0;
  for (const auto& [index, subs] : identity) {
    const auto it = yaml.find(index);
    if (it == yaml.end()) ++added_objects;
    for (unsigned s : subs)
      if (it == yaml.end() || !it->second.count(s)) ++added_entries;
  }

  // 1C00h (SM communication types) is added from the profile's SM list where the table lacks it.
  const profile::ProductProfile product = profile::load_profile(id);
  if (!yaml.count(0x1C00)) {
    ++added_objects;
    added_entries += 1 + product.sync_managers.size();
  }

  const auto t0 = std::chrono::steady_clock::now();
  const Dictionary d = Dictionary::load(product);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  RecordProperty("load_ms", std::to_string(ms));
  std::printf("[ load     ] %s: %zu objects, %zu entries in %.1f ms\n", id.c_str(), d.objects().size(),
              d.entry_count(), ms);

  EXPECT_EQ(d.objects().size(), yaml.size() + added_objects);
  EXPECT_EQ(d.entry_count(), yaml_entries + added_entries);
  for (const auto& [index, subs] : yaml) {
    const ObjectDesc* o = d.find(index);
    ASSERT_NE(o, nullptr) << std::hex << index;
    for (unsigned s : subs) EXPECT_NE(o->entry(static_cast<std::uint8_t>(s)), nullptr) << std::hex << index << ":" << s;
  }
}

TEST_P(OdProduct, IdentityObjectsEqualTheProfile) {
  const profile::ProductProfile p = profile::load_profile(GetParam());
  const Dictionary d = Dictionary::load(p);
  const ObjectStore s(d);
  EXPECT_EQ(read_unsigned(s, 0x1000, 0), p.identity.device_type);
  EXPECT_EQ(read_string(s, 0x1008, 0), p.identity.device_name);
  EXPECT_EQ(read_string(s, 0x1009, 0), p.identity.hardware_version);
  EXPECT_EQ(read_string(s, 0x100A, 0), p.identity.software_version);
  EXPECT_EQ(read_unsigned(s, 0x1018, 0), 4u);
  EXPECT_EQ(read_unsigned(s, 0x1018, 1), p.identity.vendor_id);
  EXPECT_EQ(read_unsigned(s, 0x1018, 2), p.identity.product_code);
  EXPECT_EQ(read_unsigned(s, 0x1018, 3), p.identity.revision);
  EXPECT_EQ(read_unsigned(s, 0x1018, 4), p.identity.serial);
  for (std::uint16_t index : {0x1000, 0x1008, 0x1009, 0x100A, 0x1018})
    for (const EntryDesc& e : d.find(index)->entries) EXPECT_EQ(e.access & access::kWriteAll, 0) << std::hex << index;
}

TEST_P(OdProduct, ValuesSitSideBySideWithoutOverlap) {
  const Dictionary d = Dictionary::load(profile::load_profile(GetParam()));
  std::uint32_t next = 0;
  for (const ObjectDesc& o : d.objects()) {
    for (const EntryDesc& e : o.entries) {
      EXPECT_EQ(e.value_offset, next) << std::hex << e.index << ":" << int(e.subindex);
      EXPECT_EQ(e.value_bytes, std::max<std::uint32_t>(1, (e.bit_length + 7u) / 8u));
      EXPECT_EQ(e.default_value.size(), e.value_bytes);
      EXPECT_EQ(e.index, o.index);
      next += e.value_bytes;
    }
  }
  EXPECT_EQ(d.value_bytes(), next);
}

TEST_P(OdProduct, EveryDefaultLiesInItsRange) {
  const Dictionary d = Dictionary::load(profile::load_profile(GetParam()));
  const ObjectStore s(d);
  for (const ObjectDesc& o : d.objects()) {
    for (const EntryDesc& e : o.entries) {
      if (is_string(e.type)) continue;
      std::int64_t v = 0;
      const auto raw = s.raw(e);
      for (std::size_t i = 0; i < raw.size(); ++i) v |= std::int64_t{raw[i]} << (8 * i);
      if (is_signed(e.type) && (raw.back() & 0x80)) v -= std::int64_t{1} << (8 * raw.size());
      if (e.min) {
        EXPECT_GE(v, *e.min) << std::hex << e.index << ":" << int(e.subindex);
      }
      if (e.max) {
        EXPECT_LE(v, *e.max) << std::hex << e.index << ":" << int(e.subindex);
      }
    }
  }
}

TEST(OdDictionary, A6bAccessAndPdoBitsFollowTheTable) {
  const Dictionary d = Dictionary::load(profile::load_profile("a6b"));
  // 6040h rw RxPDO, 6041h ro TxPDO (ch. 9).
  EXPECT_EQ(d.find(0x6040, 0)->access, access::kReadAll | access::kWriteAll | access::kRxPdoMappable);
  EXPECT_EQ(d.find(0x6041, 0)->access, access::kReadAll | access::kTxPdoMappable);
  // 1C12h: writable in PreOp only (L6902), not mappable.
  EXPECT_EQ(d.find(0x1C12, 1)->access, access::kReadAll | access::kWritePreOp);
  // Attribute X (unchangeable or unsupported) on an rw row: 607Bh:01, 6082h.
  EXPECT_EQ(d.find(0x607B, 1)->access & access::kWriteAll, 0);
  EXPECT_EQ(d.find(0x6082, 0)->access & access::kWriteAll, 0);
  // '-' access (for manufacturer's use): readable only, not mappable.
  EXPECT_EQ(d.find(0x4D13, 0)->access, access::kReadAll);
  EXPECT_EQ(d.find(0x6040, 0)->units, "");
  EXPECT_EQ(d.find(0x6085, 0)->units, "指令单位/s²");
  EXPECT_EQ(d.find(0x6040, 0)->manual_line > 34129, true);
}

TEST(OdDictionary, NullDefaultsAreZeroClampedIntoTheRange) {
  const Dictionary d = Dictionary::load(profile::load_profile("a6b"));
  const ObjectStore s(d);
  // A6B prints no defaults. 1C12h:01 ranges 1600h-1603h, 4D35h:00 is 2..2, 6040h 0..65535.
  EXPECT_EQ(read_unsigned(s, 0x1C12, 1), 0x1600u);
  EXPECT_EQ(read_unsigned(s, 0x4D35, 0), 2u);
  EXPECT_EQ(read_unsigned(s, 0x6040, 0), 0u);
}

TEST(OdDictionary, PrintedDefaultsAreKept) {
  const Dictionary d = Dictionary::load(profile::load_profile("ds1000a"));
  const ObjectStore s(d);
  EXPECT_EQ(read_unsigned(s, 0x6085, 0), 10000000u);   // L4981
  EXPECT_EQ(read_unsigned(s, 0x1C12, 0), 1u);
  EXPECT_EQ(read_unsigned(s, 0x1C12, 1), 0x1600u);
}

TEST(OdDictionary, StringsWithoutADefaultGetSixteenBytes) {
  const Dictionary d = Dictionary::load(profile::load_profile("a6b"));
  EXPECT_EQ(d.find(0x4D15, 0)->type, DataType::VisibleString);
  EXPECT_EQ(d.find(0x4D15, 0)->bit_length, 128);
  EXPECT_EQ(d.find(0x10F3, 6)->type, DataType::OctetString);
  EXPECT_EQ(d.find(0x10F3, 6)->bit_length, 128);   // diagnosis message, 16 bytes (L9106-L9134)
  // Identity strings are exactly the profile's text.
  EXPECT_EQ(d.find(0x1008, 0)->bit_length, 8 * std::string("MADLN15BE").size());
}

TEST(OdDictionary, MixedLanguageNamesUseTheirEnglishPart) {
  const Dictionary d = Dictionary::load(profile::load_profile("ds5c1"));
  const YAML::Node root = YAML::LoadFile(source_file("ds5c1"));
  int checked = 0;
  for (const auto& o : root["objects"]) {
    if (!o["name_en"]) continue;
    EXPECT_EQ(d.find(o["index"].as<std::uint16_t>())->name, o["name_en"].as<std::string>());
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

// ---- hand-written files -------------------------------------------------------------------

const char* kVarU16 =
    "  - index: 0x2000\n"
    "    name: \"Speed limit\"\n"
    "    object_code: VAR\n"
    "    line: 10\n"
    "    entries:\n"
    "      - subindex: 0x00\n"
    "        name: \"Speed limit\"\n"
    "        data_type: I16\n"
    "        access: rw\n"
    "        pdo: rx\n"
    "        default: null\n"
    "        min: 100\n"
    "        max: 3000\n"
    "        units: \"r/min\"\n"
    "        line: 10\n";

std::string load_error(const std::string& yaml, std::string* file = nullptr,
                       const profile::ProductProfile& p = test_product()) {
  TempObjectsDir dir(p.id, yaml);
  if (file) *file = dir.file(p.id);
  try {
    Dictionary::load(p, dir.path());
  } catch (const profile::ProfileError& e) {
    return e.what();
  }
  return {};
}

TEST(OdDictionaryFile, AHandWrittenFileLoadsWithTheRules) {
  TempObjectsDir dir("odtest", yaml_header("odtest", 1, 1) + kVarU16);
  const Dictionary d = Dictionary::load(test_product(), dir.path());
  const EntryDesc* e = d.find(0x2000, 0);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->type, DataType::Integer16);
  EXPECT_EQ(e->bit_length, 16);
  EXPECT_EQ(e->access, access::kReadAll | access::kWriteAll | access::kRxPdoMappable);
  EXPECT_EQ(e->min, 100);
  EXPECT_EQ(e->max, 3000);
  EXPECT_EQ(e->default_value, (std::vector<std::uint8_t>{100, 0}));   // null -> 0 -> clamped to 100
  EXPECT_EQ(e->units, "r/min");
  EXPECT_EQ(e->manual_line, 10);
  EXPECT_FALSE(e->synthesized);
  // Plus the five identity objects the file lacks, synthesized.
  EXPECT_EQ(d.objects().size(), 6u);
  EXPECT_TRUE(d.find(0x1018, 4)->synthesized);
  EXPECT_EQ(d.find(0x1018)->code, ObjectCode::Record);
}

TEST(OdDictionaryFile, AProductWithoutObjectsYamlHasItsIdentityOnly) {
  const Dictionary d = Dictionary::load(test_product("no_such_product"));
  EXPECT_EQ(d.objects().size(), 5u);
  EXPECT_EQ(d.entry_count(), 9u);
  const ObjectStore s(d);
  EXPECT_EQ(read_string(s, 0x100A, 0), "SW 1.2.3");
  EXPECT_EQ(read_unsigned(s, 0x1018, 2), 0x00ABCDEFu);
}

TEST(OdDictionaryFile, AnIncompleteIdentityRecordIsCompleted) {
  const std::string yaml = yaml_header("odtest", 1, 2) +
                           "  - index: 0x1018\n    name: \"Identity\"\n    object_code: RECORD\n    line: 5\n"
                           "    entries:\n"
                           "      - {subindex: 0x00, name: \"n\", data_type: U8, access: ro, pdo: \"no\", default: 1, min: 0, max: 1, units: null, line: 5}\n"
                           "      - {subindex: 0x01, name: \"Vendor\", data_type: U32, access: ro, pdo: \"no\", default: 7, min: null, max: null, units: null, line: 6}\n";
  TempObjectsDir dir("odtest", yaml);
  const Dictionary d = Dictionary::load(test_product(), dir.path());
  const ObjectStore s(d);
  EXPECT_EQ(d.find(0x1018)->entries.size(), 5u);
  EXPECT_EQ(read_unsigned(s, 0x1018, 0), 4u);
  EXPECT_EQ(read_unsigned(s, 0x1018, 1), 0x12345678u);   // the profile wins over the table's 7
  EXPECT_FALSE(d.find(0x1018, 1)->synthesized);
  EXPECT_TRUE(d.find(0x1018, 3)->synthesized);
}

TEST(OdDictionaryFile, FieldsThatMayBeNullMayBeLeftOut) {
  // Only product, objects, index, name, object_code, entries, subindex, name and data_type.
  TempObjectsDir dir("odtest",
                     "product: odtest\nobjects:\n"
                     "  - {index: 0x2200, name: \"Bare\", object_code: VAR, entries: [{subindex: 0, name: \"Bare\", data_type: U8}]}\n");
  const Dictionary d = Dictionary::load(test_product(), dir.path());
  const EntryDesc* e = d.find(0x2200, 0);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->access, access::kReadAll);   // access null = ro
  EXPECT_FALSE(e->min.has_value());
  EXPECT_EQ(e->default_value, (std::vector<std::uint8_t>{0}));
  EXPECT_EQ(e->manual_line, 0);
}

struct BadFile {
  const char* what;
  std::string yaml;
  std::string field;    // must appear in the message
  int line;             // 1-based line the message must name
};

class OdDictionaryBadFile : public ::testing::TestWithParam<BadFile> {};

std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

// Line numbers: the header is 7 lines, kVarU16 starts on line 8; its entry's fields on 14-22.
INSTANTIATE_TEST_SUITE_P(
    Errors, OdDictionaryBadFile,
    ::testing::Values(
        BadFile{"unknown_type", yaml_header("odtest", 1, 1) + with(kVarU16, "I16", "F64"), "objects[0] (0x2000).entries[0].data_type", 15},
        BadFile{"default_out_of_range", yaml_header("odtest", 1, 1) + with(kVarU16, "default: null", "default: 5000"), "entries[0].default", 18},
        BadFile{"default_not_integer", yaml_header("odtest", 1, 1) + with(kVarU16, "default: null", "default: fast"), "entries[0].default", 18},
        BadFile{"min_above_max", yaml_header("odtest", 1, 1) + with(kVarU16, "min: 100", "min: 4000"), "entries[0].max", 20},
        BadFile{"range_beyond_type", yaml_header("odtest", 1, 1) + with(kVarU16, "max: 3000", "max: 40000"), "entries[0].max", 20},
        BadFile{"bad_access", yaml_header("odtest", 1, 1) + with(kVarU16, "access: rw", "access: wo"), "entries[0].access", 16},
        BadFile{"bad_pdo", yaml_header("odtest", 1, 1) + with(kVarU16, "pdo: rx", "pdo: both"), "entries[0].pdo", 17},
        BadFile{"bad_state", yaml_header("odtest", 1, 1) + with(kVarU16, "pdo: rx", "writable_in: [BOOT]\n        pdo: rx"), "entries[0].writable_in", 17},
        BadFile{"unknown_field", yaml_header("odtest", 1, 1) + with(kVarU16, "units:", "unit: x\n        units:"), "entries[0].unit", 21},
        BadFile{"missing_field", yaml_header("odtest", 1, 1) + with(kVarU16, "        data_type: I16\n", ""), "entries[0].data_type", 13},
        BadFile{"bad_object_code", yaml_header("odtest", 1, 1) + with(kVarU16, "VAR", "STRUCT"), "objects[0].object_code", 10},
        BadFile{"wrong_object_count", yaml_header("odtest", 2, 1) + kVarU16, "object_count", 4},
        BadFile{"wrong_entry_count", yaml_header("odtest", 1, 3) + kVarU16, "entry_count", 5},
        BadFile{"unsorted_objects", yaml_header("odtest", 2, 2) + kVarU16 + with(kVarU16, "0x2000", "0x1FFF"), "objects[1].index", 23},
        BadFile{"not_yaml", yaml_header("odtest", 1, 1) + "  - index: [0x2000\n", "", 9}));

TEST_P(OdDictionaryBadFile, IsRefusedNamingFileLineAndField) {
  std::string file;
  const std::string message = load_error(GetParam().yaml, &file);
  ASSERT_FALSE(message.empty()) << GetParam().what;
  EXPECT_EQ(message.rfind(file + ":" + std::to_string(GetParam().line) + ":", 0), 0u) << message;
  EXPECT_NE(message.find(GetParam().field), std::string::npos) << message;
}

TEST(OdDictionaryFile, AFileOfAnotherProductIsRefused) {
  std::string file;
  const std::string message = load_error(yaml_header("other", 1, 1) + kVarU16, &file);
  EXPECT_NE(message.find(file), std::string::npos) << message;
  EXPECT_NE(message.find("product"), std::string::npos) << message;
}

}  // namespace
}  // namespace vdrive::od
