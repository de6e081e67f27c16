#pragma once
// Finds and loads product profiles. Profiles are data files (profiles/<id>/profile.yaml) embedded
// into the binary at build time, so `vdrive` runs anywhere; a directory can override them.
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::profile {

// A profile that is missing or wrong; what() names the product/file and the field.
class ProfileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Product ids known to this build: the folder names under profiles/, sorted.
std::vector<std::string> known_products();

// Loads a product by id from the embedded profiles, or from `<profile_dir>/<id>/profile.yaml`
// when profile_dir is not empty. Throws ProfileError.
ProductProfile load_profile(std::string_view id, const std::string& profile_dir = {});

}  // namespace vdrive::profile
