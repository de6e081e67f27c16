#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
std::vector<std::string> known_products() { return {}; }
ProductProfile load_profile(std::string_view id, const std::string&) {
  throw ProfileError("unknown product '" + std::string(id) + "'");
}
}  // namespace vdrive::profile
