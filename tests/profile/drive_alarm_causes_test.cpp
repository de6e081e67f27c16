// profile.yaml drive.alarms: the causes the fault injector needs (main_power_off, abort_connection,
// supply_alarms_only_when_enabled) are required like every other key; a missing or mistyped one,
// or a code that is not in alarms.yaml, is refused naming the file, the line and the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "vdrive/profile/embedded_profiles.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
namespace {

namespace fs = std::filesystem;

std::string embedded(std::string_view id, std::string* alarms, std::string* motors) {
  for (const auto& e : embedded_profiles())
    if (e.id == id) {
      *alarms = std::string(e.alarms_yaml);
      *motors = std::string(e.motors_yaml);
      return std::string(e.yaml);
    }
  ADD_FAILURE() << "no embedded profile " << id;
  return {};
}

int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

// Loads product `id` with profile.yaml replaced by `profile`; returns the error ("" if none) and
// sets `dir` to the product directory used.
std::string load_with(const std::string& id, const std::string& profile, std::string* dir) {
  std::string alarms, motors;
  embedded(id, &alarms, &motors);
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path root = fs::temp_directory_path() / ("vdrive_alarm_causes_test_" + std::string(info->name()));
  fs::create_directories(root / id);
  std::ofstream(root / id / "profile.yaml") << profile;
  std::ofstream(root / id / "alarms.yaml") << alarms;
  std::ofstream(root / id / "motors.yaml") << motors;
  *dir = (root / id).string();
  std::string error;
  try {
    load_profile(id, root.string());
  } catch (const ProfileError& e) {
    error = e.what();
  }
  fs::remove_all(root);
  return error;
}

TEST(ProfileDriveAlarmCauses, ProductsNameTheirSupplyAlarms) {
  EXPECT_EQ(load_profile("a6b").drive.alarms.main_power_off, "13.1");      // L32684
  EXPECT_EQ(load_profile("a6b").drive.alarms.undervoltage, "13.0");        // L32682
  EXPECT_EQ(load_profile("a6b").drive.alarms.abort_connection, "88.0");    // L33767
  EXPECT_TRUE(load_profile("a6b").drive.alarms.supply_alarms_only_when_enabled);
  EXPECT_EQ(load_profile("ds5c1").drive.alarms.main_power_off, "E-041");   // L7173-L7174
  EXPECT_FALSE(load_profile("ds5c1").drive.alarms.supply_alarms_only_when_enabled);
  EXPECT_EQ(load_profile("ds1000a").drive.alarms.main_power_off, "");      // no independent main power, L5241
}

TEST(ProfileDriveAlarmCauses, NewKeysAreRequired) {
  for (const char* key : {"main_power_off", "abort_connection", "supply_alarms_only_when_enabled"}) {
    SCOPED_TRACE(key);
    std::string alarms, motors;
    std::string text = embedded("ds5c1", &alarms, &motors);
    const auto pos = text.find(std::string("\n    ") + key + ":");
    ASSERT_NE(pos, std::string::npos);
    text.erase(pos, text.find('\n', pos + 1) - pos);
    std::string dir;
    const std::string error = load_with("ds5c1", text, &dir);
    const int alarms_line = line_of(text, "\n  alarms:") + 1;
    EXPECT_EQ(error, dir + "/profile.yaml:" + std::to_string(alarms_line) + ": drive.alarms." + key + ": missing");
  }
}

TEST(ProfileDriveAlarmCauses, WrongTypeNamesLineAndKey) {
  std::string alarms, motors;
  std::string text = embedded("a6b", &alarms, &motors);
  const std::string from = "supply_alarms_only_when_enabled: true";
  text.replace(text.find(from), from.size(), "supply_alarms_only_when_enabled: sometimes");
  std::string dir;
  const std::string error = load_with("a6b", text, &dir);
  EXPECT_EQ(error, dir + "/profile.yaml:" + std::to_string(line_of(text, "supply_alarms_only_when_enabled: sometimes")) +
                       ": drive.alarms.supply_alarms_only_when_enabled: expected true or false");
}

TEST(ProfileDriveAlarmCauses, CodeMustBeInTheAlarmTable) {
  std::string alarms, motors;
  std::string text = embedded("a6b", &alarms, &motors);
  const std::string from = "main_power_off: \"13.1\"";
  text.replace(text.find(from), from.size(), "main_power_off: \"13.9\"");
  std::string dir;
  const std::string error = load_with("a6b", text, &dir);
  EXPECT_EQ(error, dir + "/profile.yaml: drive.alarms.main_power_off: '13.9' is not an alarm of alarms.yaml");
}

}  // namespace
}  // namespace vdrive::profile
