#pragma once
// The identity objects (CiA 301 / ETG.1000.6): 1000h device type, 1008h/1009h/100Ah name and
// versions, 1018h vendor ID, product code, revision, serial. Their values come from the profile,
// the single source of identity, whatever objects.yaml prints; objects or entries the table lacks
// are added (synthesized = true).
#include <vector>

#include "vdrive/od/dictionary.hpp"

namespace vdrive::od {

// `objects` sorted by index before and after.
void apply_identity(std::vector<ObjectDesc>& objects, const profile::Identity& identity);

}  // namespace vdrive::od
