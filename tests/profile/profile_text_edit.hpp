#pragma once
// Loading a product whose profile.yaml text a test has edited: the embedded files of a product,
// written to a temporary folder with one change, loaded by the normal loader. For tests that check
// how a bad value is refused (file, line and key in the message).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "vdrive/profile/embedded_profiles.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile::test {

struct ProductTexts {
  std::string profile, alarms, motors;
};

inline ProductTexts embedded_texts(std::string_view id) {
  for (const auto& e : embedded_profiles())
    if (e.id == id) return {std::string(e.yaml), std::string(e.alarms_yaml), std::string(e.motors_yaml)};
  ADD_FAILURE() << "no embedded profile " << id;
  return {};
}

inline std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

// 1-based line of the first occurrence of `needle`.
inline int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

struct LoadResult {
  std::string error, dir;  // error "" when the product loaded; dir = the product folder used
};

inline LoadResult load_texts(const std::string& id, const ProductTexts& t) {
  namespace fs = std::filesystem;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path root = fs::temp_directory_path() / ("vdrive_profile_edit_" + std::string(info->name()));
  fs::create_directories(root / id);
  std::ofstream(root / id / "profile.yaml") << t.profile;
  // An empty text leaves the file out (a test of the missing file).
  if (!t.alarms.empty()) std::ofstream(root / id / "alarms.yaml") << t.alarms;
  if (!t.motors.empty()) std::ofstream(root / id / "motors.yaml") << t.motors;
  LoadResult r{{}, (root / id).string()};
  try {
    load_profile(id, root.string());
  } catch (const ProfileError& e) {
    r.error = e.what();
  }
  fs::remove_all(root);
  return r;
}

// "<dir>/<file>:<line of needle>: ", the start of the loader's message about that line of `file`.
inline std::string where(const LoadResult& r, const std::string& file, const std::string& text,
                         const std::string& needle) {
  return r.dir + "/" + file + ":" + std::to_string(line_of(text, needle)) + ": ";
}
inline std::string at(const LoadResult& r, const std::string& text, const std::string& needle) {
  return where(r, "profile.yaml", text, needle);
}

}  // namespace vdrive::profile::test
