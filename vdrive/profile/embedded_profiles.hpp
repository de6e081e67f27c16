#pragma once
// The profile.yaml and objects.yaml texts compiled into the binary. The definition is generated at
// build time by profiles/embed_profiles.cmake (raw string literals of profiles/<id>/*.yaml).
#include <span>
#include <string>
#include <string_view>

namespace vdrive::profile {

struct EmbeddedProfile {
  std::string_view id;    // directory name under profiles/
  std::string_view yaml;  // the file's text, byte for byte
  // profiles/<id>/objects.yaml, byte for byte once the pieces are joined (empty when there is
  // none). In pieces of at most 60000 bytes cut after a newline, because ISO C++ only promises
  // 65536-byte string literals (-Woverlength-strings) and the A6B file is ~430 KB.
  std::span<const std::string_view> objects_yaml;
  std::string_view alarms_yaml;  // profiles/<id>/alarms.yaml, byte for byte ("" when there is none)
  std::string_view motors_yaml;  // profiles/<id>/motors.yaml, byte for byte ("" when there is none)
};

// The joined objects.yaml text of `profile` (one allocation; call at load time).
std::string embedded_objects_yaml(const EmbeddedProfile& profile);

// All embedded profiles, sorted by id.
std::span<const EmbeddedProfile> embedded_profiles();

}  // namespace vdrive::profile
