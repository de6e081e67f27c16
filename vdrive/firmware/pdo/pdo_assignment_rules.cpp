#include "vdrive/firmware/pdo/pdo_assignment_rules.hpp"

#include <algorithm>
#include <array>

#include "vdrive/firmware/pdo/pdo_mapping.hpp"

namespace vdrive::firmware::pdo {

AssignmentFault check_assignment_rules(const od::ObjectStore& objects, std::uint16_t assign_index,
                                       const std::vector<profile::PdoObjectRule>& rules) {
  std::array<std::uint16_t, 255> assigned{};
  const std::uint32_t count = std::min<std::uint32_t>(read_unsigned(objects, assign_index, 0), assigned.size());
  for (std::uint32_t i = 0; i < count; ++i)
    assigned[i] = static_cast<std::uint16_t>(read_unsigned(objects, assign_index, static_cast<std::uint8_t>(i + 1)));
  const auto first = assigned.begin(), last = assigned.begin() + count;
  auto is_assigned = [&](std::uint16_t pdo) { return std::find(first, last, pdo) != last; };
  for (const profile::PdoObjectRule& rule : rules) {
    if (rule.mandatory && !is_assigned(rule.index)) return AssignmentFault::MandatoryMissing;
    if (!is_assigned(rule.index)) continue;
    for (const std::uint16_t other : rule.excludes)
      if (other != rule.index && is_assigned(other)) return AssignmentFault::Excluded;
  }
  return AssignmentFault::Ok;
}

}  // namespace vdrive::firmware::pdo
