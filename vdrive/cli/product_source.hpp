#pragma once
// What `--drive` names in the commands that describe a product (od, sii, esi): a built-in or
// --profile-dir product id, or a device of an ESI file (FILE.xml[:PRODUCT[:REVISION]]), with its
// profile, object dictionary and SII image as the network would serve them. Unknown products and
// broken files are CliError exit 2, with the known products or the file's line and element.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vdrive/od/dictionary.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::cli {

struct ProductSource {
  profile::ProductProfile profile;
  std::shared_ptr<const od::Dictionary> dictionary;
  std::vector<std::uint8_t> sii_image;
};

ProductSource load_product_source(const std::string& drive, const std::string& profile_dir);

}  // namespace vdrive::cli
