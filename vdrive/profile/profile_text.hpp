#pragma once
// A product profile from text in memory, read exactly as load_profile reads the files of
// `<dir>/` (profile.yaml, alarms.yaml, motors.yaml): for tools and fuzzing that hold the text, not
// a directory. Every mistake is a ProfileError naming the file (`dir` + the file's name), the line
// and the field.
#include <string>
#include <string_view>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::profile {

ProductProfile parse_profile_text(std::string_view id, const std::string& profile_yaml, std::string_view alarms_yaml,
                                  std::string_view motors_yaml, const std::string& dir);

}  // namespace vdrive::profile
