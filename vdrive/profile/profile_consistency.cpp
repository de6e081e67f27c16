// Rules that tie profile.yaml sections together.
#include <algorithm>

#include <fmt/format.h>

#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {
namespace {

void check_default_pdos(const std::vector<PdoSpec>& pdos, const std::vector<PdoObjectRule>& objects,
                        std::uint8_t max_assigned, std::uint16_t max_bytes, std::string_view key,
                        const YamlMapReader& root) {
  unsigned assigned = 0, bits = 0;
  for (const PdoSpec& pdo : pdos) {
    const auto rule = std::find_if(objects.begin(), objects.end(),
                                   [&](const PdoObjectRule& r) { return r.index == pdo.index; });
    if (rule == objects.end())
      root.fail(key, fmt::format("default PDO 0x{:04X} is not among pdo_rules' mapping objects", pdo.index));
    if (pdo.entries.size() > rule->max_entries)
      root.fail(key, fmt::format("default PDO 0x{:04X} has {} entries, pdo_rules allows {}", pdo.index,
                                 pdo.entries.size(), rule->max_entries));
    if (pdo.fixed != rule->fixed)
      root.fail(key, fmt::format("default PDO 0x{:04X}: fixed differs from pdo_rules", pdo.index));
    if (pdo.sync_manager == 0xFF) continue;
    ++assigned;
    for (const PdoEntrySpec& e : pdo.entries) bits += e.bit_length;
  }
  if (assigned > max_assigned)
    root.fail(key, fmt::format("{} PDOs assigned by default, pdo_rules allows {}", assigned, max_assigned));
  if ((bits + 7) / 8 > max_bytes)
    root.fail(key, fmt::format("default mapping is {} bytes, pdo_rules allows {}", (bits + 7) / 8, max_bytes));
}

}  // namespace

void check_consistency(const ProductProfile& p, const YamlMapReader& root) {
  check_default_pdos(p.rx_pdos, p.pdo_rules.rx_objects, p.pdo_rules.max_rx_assigned, p.pdo_rules.max_rx_bytes,
                     "rx_pdos", root);
  check_default_pdos(p.tx_pdos, p.pdo_rules.tx_objects, p.pdo_rules.max_tx_assigned, p.pdo_rules.max_tx_bytes,
                     "tx_pdos", root);
  for (const ModeCycleLimit& l : p.sync.mode_min_cycle)
    if (std::find(p.modes.modes.begin(), p.modes.modes.end(), l.mode) == p.modes.modes.end())
      root.fail("sync", fmt::format("mode_min_cycle names mode {}, which is not in modes.modes", l.mode));
}

}  // namespace vdrive::profile
