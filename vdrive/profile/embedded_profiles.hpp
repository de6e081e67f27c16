#pragma once
// The profile.yaml texts compiled into the binary. The definition is generated at build time by
// profiles/embed_profiles.cmake (one raw string literal per profiles/<id>/profile.yaml).
#include <span>
#include <string_view>

namespace vdrive::profile {

struct EmbeddedProfile {
  std::string_view id;    // directory name under profiles/, e.g. "a6b"
  std::string_view yaml;  // the file's text, byte for byte
};

// All embedded profiles, sorted by id.
std::span<const EmbeddedProfile> embedded_profiles();

}  // namespace vdrive::profile
