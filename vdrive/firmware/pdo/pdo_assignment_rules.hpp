#pragma once
// The rules an ESI file gives a PDO assignment (RxPdo/TxPdo@Mandatory, <Exclude>), checked at
// PreOp->SafeOp with the mapping: every mandatory PDO of the direction is assigned, and no two
// assigned PDOs exclude each other. Products without such rules pass.
#include <cstdint>
#include <vector>

#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/pdo_spec.hpp"

namespace vdrive::firmware::pdo {

enum class AssignmentFault : std::uint8_t { Ok, MandatoryMissing, Excluded };

// `assign_index` is 1C12h or 1C13h; `objects` the direction's mapping objects with their rules.
AssignmentFault check_assignment_rules(const od::ObjectStore& objects, std::uint16_t assign_index,
                                       const std::vector<profile::PdoObjectRule>& rules);

}  // namespace vdrive::firmware::pdo
