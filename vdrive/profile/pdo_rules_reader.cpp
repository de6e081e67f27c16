// profile.yaml `pdo_rules`: which mapping objects exist, how many may be assigned, size limits and
// the ESM states in which the mapping may change.
#include <fmt/format.h>

#include "vdrive/profile/profile_sections.hpp"

namespace vdrive::profile {
namespace {

std::vector<PdoObjectRule> read_objects(YamlMapReader& m, std::string_view key, std::uint16_t first) {
  const YAML::Node seq = m.sequence(key);
  std::vector<PdoObjectRule> out;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader o = m.element(seq, key, i);
    PdoObjectRule r;
    r.index = o.u16("index");
    if (r.index < first || r.index > first + 0x1FF)
      o.fail("index", fmt::format("expected a mapping object index in 0x{:04X}..0x{:04X}", first, first + 0x1FF));
    if (!out.empty() && r.index <= out.back().index) o.fail("index", "expected ascending, distinct indexes");
    r.fixed = o.boolean("fixed");
    r.max_entries = o.u8("max_entries");
    if (r.max_entries == 0 || r.max_entries > 254) o.fail("max_entries", "expected 1..254");
    o.finish();
    out.push_back(r);
  }
  return out;
}

EsmStateSet read_states(YamlMapReader& m, std::string_view key) {
  const YAML::Node seq = m.sequence(key);
  EsmStateSet set = 0;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const std::string s = seq[i].IsScalar() ? seq[i].Scalar() : std::string();
    const EsmStateSet bit = s == "init"     ? kStateInit
                            : s == "preop"  ? kStatePreOp
                            : s == "safeop" ? kStateSafeOp
                            : s == "op"     ? kStateOp
                            : s == "boot"   ? kStateBoot
                                            : 0;
    if (bit == 0)
      throw_at(m.file(), seq[i].Mark(),
               std::string(key) + "[" + std::to_string(i) + "]: expected one of init, preop, safeop, op, boot");
    set |= bit;
  }
  return set;
}

}  // namespace

PdoRules read_pdo_rules(YamlMapReader m) {
  PdoRules r;
  r.rx_objects = read_objects(m, "rx_objects", 0x1600);
  r.tx_objects = read_objects(m, "tx_objects", 0x1A00);
  r.max_rx_assigned = m.u8("max_rx_assigned");
  r.max_tx_assigned = m.u8("max_tx_assigned");
  if (r.max_rx_assigned > r.rx_objects.size()) m.fail("max_rx_assigned", "exceeds the number of rx_objects");
  if (r.max_tx_assigned > r.tx_objects.size()) m.fail("max_tx_assigned", "exceeds the number of tx_objects");
  r.max_rx_bytes = m.u16("max_rx_bytes");
  r.max_tx_bytes = m.u16("max_tx_bytes");
  r.assign_writable = m.boolean("assign_writable");
  r.mapping_writable = m.boolean("mapping_writable");
  bool any_free = false;
  for (const auto* list : {&r.rx_objects, &r.tx_objects})
    for (const auto& o : *list) any_free = any_free || !o.fixed;
  if (r.mapping_writable != any_free)
    m.fail("mapping_writable", "must be true exactly when some mapping object is not fixed");
  r.writable_states = read_states(m, "writable_states");
  r.sub0_must_be_zero = m.boolean("sub0_must_be_zero");
  r.wrong_state_abort = m.u32("wrong_state_abort");
  if ((r.wrong_state_abort >> 24) == 0) m.fail("wrong_state_abort", "expected an SDO abort code (0x05xxxxxx-0x08xxxxxx)");
  r.checked_at_safeop = m.boolean("checked_at_safeop");
  r.byte_aligned_total = m.boolean("byte_aligned_total");
  if (m.has("sm_control_mode_checked")) r.sm_control_mode_checked = m.boolean("sm_control_mode_checked");
  if (m.has("unused_sm_must_be_disabled")) r.unused_sm_must_be_disabled = m.boolean("unused_sm_must_be_disabled");
  m.finish();
  return r;
}

}  // namespace vdrive::profile
