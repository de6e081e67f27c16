#include "vdrive/cli/product_source.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/exit_codes.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::cli {

ProductSource load_product_source(const std::string& drive, const std::string& profile_dir) {
  if (esi::is_esi_reference(drive)) {
    try {
      const std::shared_ptr<const esi::ImportedDevice> d = esi::load_esi_device(drive);
      return {d->profile, d->dictionary, d->sii_image};
    } catch (const profile::ProfileError& e) {
      throw CliError(kExitBadArguments, fmt::format("--drive: {}", e.what()));
    }
  }
  const std::vector<std::string> known = profile::known_products();
  if (profile_dir.empty() && std::find(known.begin(), known.end(), drive) == known.end()) {
    throw CliError(kExitBadArguments,
                   fmt::format("--drive: unknown product '{}' (known: {}; or an ESI device, FILE.xml[:PRODUCT[:REVISION]])",
                               drive, known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
  }
  ProductSource s;
  s.profile = profile::load_profile(drive, profile_dir);
  s.dictionary = od::shared_dictionary(s.profile, profile_dir);
  s.sii_image = profile::build_sii_image(s.profile);
  return s;
}

}  // namespace vdrive::cli
