// `vdrive od` and `vdrive sii` as a user runs them: the built binary, its output checked against
// the dictionary and SII image built in-process, and the documented errors and exit codes.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>

#include "tests/support/child_process.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

#ifndef VDRIVE_BINARY
#error "tests/CMakeLists.txt defines VDRIVE_BINARY as the path of the built vdrive program"
#endif

namespace vdrive::od {
namespace {

vdrive::test::ProcessResult vdrive(const std::vector<std::string>& args) {
  return vdrive::test::run_process(VDRIVE_BINARY, args);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

void expect_one_error_line(const vdrive::test::ProcessResult& r, const std::string& must_contain) {
  EXPECT_EQ(r.err.rfind("vdrive: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(must_contain), std::string::npos) << r.err;
}

class OdCommand : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Products, OdCommand, ::testing::Values("a6b", "ds5c1", "ds1000a"));

TEST_P(OdCommand, PrintsAHeaderAndOneLinePerEntry) {
  const Dictionary d = Dictionary::load(profile::load_profile(GetParam()));
  const auto r = vdrive({"od", "--drive", GetParam()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), d.entry_count() + 1);
  EXPECT_EQ(out[0].rfind("INDEX", 0), 0u);
  std::size_t row = 1;
  for (const ObjectDesc& o : d.objects()) {
    for (const EntryDesc& e : o.entries) {
      char key[16];
      std::snprintf(key, sizeof key, "%04Xh  %02Xh ", e.index, e.subindex);
      EXPECT_EQ(out[row].rfind(key, 0), 0u) << out[row];
      EXPECT_NE(out[row].find(e.name), std::string::npos) << out[row];
      ++row;
    }
  }
}

TEST(OdCommandText, IndexSelectsOneObjectWithItsColumns) {
  for (const char* index : {"0x6040", "6040h", "24640"}) {
    const auto r = vdrive({"od", "--drive", "a6b", "--index", index});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> out = lines(r.out);
    ASSERT_EQ(out.size(), 2u) << r.out;
    EXPECT_TRUE(std::regex_search(out[1], std::regex(R"(^6040h  00h Controlword +U16 +rw +rx +0 +0\.\.65535 +-$)")))
        << out[1];
  }
  const auto r = vdrive({"od", "--drive", "a6b", "--index", "0x1C12"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), 6u) << r.out;   // 00h-04h
  EXPECT_NE(out[2].find("rw(PreOp)"), std::string::npos) << out[2];
  EXPECT_NE(out[2].find("5632..5635"), std::string::npos) << out[2];
}

TEST(OdCommandText, UnitsAreInEnglishWithTheManualsBeside) {
  auto r = vdrive({"od", "--drive", "ds5c1", "--index", "0x6064"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), 2u) << r.out;
  EXPECT_NE(out[0].find("UNITS (MANUAL)"), std::string::npos) << out[0];
  EXPECT_TRUE(std::regex_search(out[1], std::regex(R"( command unit +指令单位$)"))) << out[1];
  r = vdrive({"od", "--drive", "ds5c1", "--index", "0x6064", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["entries"][0]["units"], "command unit");
  EXPECT_EQ(j["entries"][0]["units_manual"], "指令单位");
}

TEST(OdCommandJson, MatchesTheDictionaryAndTheProfile) {
  const profile::ProductProfile p = profile::load_profile("ds1000a");
  const Dictionary d = Dictionary::load(p);
  const auto r = vdrive({"od", "--drive", "ds1000a", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["product"], "ds1000a");
  ASSERT_EQ(j["entries"].size(), d.entry_count());
  int seen = 0;
  for (const auto& e : j["entries"]) {
    const EntryDesc* desc = d.find(e["index"].get<std::uint16_t>(), e["subindex"].get<std::uint8_t>());
    ASSERT_NE(desc, nullptr);
    EXPECT_EQ(e["type"], std::string(short_name(desc->type)));
    EXPECT_EQ(e["access_bits"], desc->access);
    if (e["index"] == 0x1018 && e["subindex"] == 1) {
      EXPECT_EQ(e["default"], p.identity.vendor_id);
      ++seen;
    }
    if (e["index"] == 0x1008) {
      EXPECT_EQ(e["default"], p.identity.device_name);
      ++seen;
    }
    if (e["index"] == 0x6085) {
      EXPECT_EQ(e["default"], 10000000);
      EXPECT_EQ(e["units"], "User/s2");
      EXPECT_EQ(e["pdo"], "rx");
      EXPECT_EQ(e["manual_line"], 4981);
      ++seen;
    }
    if (e["index"] == 0x6041) {
      EXPECT_EQ(e["access"], "ro");
      EXPECT_EQ(e["pdo"], "tx");
      ++seen;
    }
  }
  EXPECT_EQ(seen, 4);
}

TEST(OdCommandErrors, AreOneLineWithTheDocumentedExitCode) {
  auto r = vdrive({"od", "--drive", "a7"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--drive: unknown product 'a7'");
  r = vdrive({"od"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--drive");
  r = vdrive({"od", "--drive", "a6b", "--index", "0x1FFFF"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--index: '0x1FFFF'");
  r = vdrive({"od", "--drive", "a6b", "--index", "0x7000"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "a6b has no object 7000h");
  EXPECT_TRUE(r.out.empty());
}

// ---- sii ----------------------------------------------------------------------------------

class SiiCommand : public ::testing::TestWithParam<std::string> {
protected:
  std::filesystem::path file_ = std::filesystem::temp_directory_path() /
                                ("vdrive_sii_test_" + std::to_string(::getpid()) + "_" + GetParam() + ".bin");
  ~SiiCommand() override { std::filesystem::remove(file_); }
};
INSTANTIATE_TEST_SUITE_P(Products, SiiCommand, ::testing::Values("a6b", "ds5c1", "ds1000a"));

TEST_P(SiiCommand, WritesTheImageTheEscLoads) {
  const auto r = vdrive({"sii", "--drive", GetParam(), "-o", file_.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::ifstream in(file_, std::ios::binary);
  const std::vector<std::uint8_t> written{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(written, profile::build_sii_image(profile::load_profile(GetParam())));
}

TEST_P(SiiCommand, HexDumpsTheSameBytesWithWordAddresses) {
  const auto r = vdrive({"sii", "--drive", GetParam(), "--hex"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::uint8_t> bytes;
  std::size_t expected_word = 0;
  for (const std::string& line : lines(r.out)) {
    ASSERT_GE(line.size(), 6u) << line;
    EXPECT_EQ(std::stoul(line.substr(0, 4), nullptr, 16), expected_word) << line;
    std::istringstream fields(line.substr(5));
    for (std::string b; fields >> b;) bytes.push_back(static_cast<std::uint8_t>(std::stoul(b, nullptr, 16)));
    expected_word += 8;
  }
  EXPECT_EQ(bytes, profile::build_sii_image(profile::load_profile(GetParam())));
}

TEST(SiiCommandErrors, AreOneLineWithTheDocumentedExitCode) {
  auto r = vdrive({"sii", "--drive", "a6b"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "-o FILE");
  r = vdrive({"sii", "--drive", "a6b", "--hex", "-o", "/tmp/x.bin"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--hex");
  r = vdrive({"sii", "--drive", "nope", "--hex"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--drive: unknown product 'nope'");
  r = vdrive({"sii", "--drive", "a6b", "-o", "/nonexistent-dir/x.bin"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, "/nonexistent-dir/x.bin");
}

}  // namespace
}  // namespace vdrive::od
