// Temporary: empty dictionary and store so everything links until the OD engine lands.
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::od {
Dictionary Dictionary::load(const profile::ProductProfile&, const std::string&) { return {}; }
ObjectStore::ObjectStore(const Dictionary& d) : dict_(d) {}
}  // namespace vdrive::od
