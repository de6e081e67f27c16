#include "vdrive/od/dictionary_cache.hpp"

#include <map>
#include <mutex>
#include <utility>

namespace vdrive::od {

std::shared_ptr<const Dictionary> shared_dictionary(const profile::ProductProfile& profile,
                                                    const std::string& profile_dir) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, std::string>, std::shared_ptr<const Dictionary>> cache;
  const std::lock_guard lock(mutex);
  auto& slot = cache[{profile.id, profile_dir}];
  if (!slot) slot = std::make_shared<const Dictionary>(Dictionary::load(profile, profile_dir));
  return slot;
}

}  // namespace vdrive::od
