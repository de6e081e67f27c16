#pragma once
// The real products for tests that need only the profile: profiles/<id>/*.yaml as compiled into
// the binary (profile::load_profile), parsed once per test binary.
#include <map>
#include <string>

#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::test {

inline const profile::ProductProfile& product(const std::string& id) {
  static std::map<std::string, profile::ProductProfile> loaded;
  auto it = loaded.find(id);
  if (it == loaded.end()) it = loaded.emplace(id, profile::load_profile(id)).first;
  return it->second;
}

}  // namespace vdrive::test
