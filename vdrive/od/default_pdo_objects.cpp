#include "vdrive/od/default_pdo_objects.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "ethercat/little_endian.hpp"
#include "ethercat/pdo_mapping_entry.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::od {

namespace {

ObjectDesc* find_object(std::vector<ObjectDesc>& objects, std::uint16_t index) {
  auto it = std::lower_bound(objects.begin(), objects.end(), index,
                             [](const ObjectDesc& o, std::uint16_t i) { return o.index < i; });
  return it != objects.end() && it->index == index ? &*it : nullptr;
}

std::uint32_t default_u32(const EntryDesc& e) {
  const std::span<const std::uint8_t> bytes(e.default_value);
  return static_cast<std::uint32_t>(ecat::get_le(bytes.first(std::min<std::size_t>(bytes.size(), 4))));
}

void set_default(EntryDesc& e, std::uint32_t value) {
  e.default_value.assign(std::max<std::uint32_t>(e.value_bytes, 1), 0);
  ecat::put_le(std::span(e.default_value).first(std::min<std::size_t>(e.default_value.size(), 4)), value);
  // The factory value must be one the drive accepts back.
  if (e.max && *e.max < static_cast<std::int64_t>(value)) e.max = value;
  if (e.min && *e.min > static_cast<std::int64_t>(value)) e.min = value;
  e.synthesized = true;
}

EntryDesc& require_entry(ObjectDesc& object, std::uint8_t subindex, const std::string& product) {
  auto* e = const_cast<EntryDesc*>(object.entry(subindex));
  if (!e)
    throw profile::ProfileError(fmt::format(
        "profiles/{}: default PDO configuration needs {:04X}h:{:02X}h, which the dictionary lacks",
        product, object.index, subindex));
  return *e;
}

// A mapping object (or 1C12h/1C13h) whose subindex 0 defaults to 0 lists nothing by default.
bool table_lists_nothing(const ObjectDesc& object) {
  const EntryDesc* sub0 = object.entry(0);
  return sub0 != nullptr && default_u32(*sub0) == 0;
}

void fill(ObjectDesc& object, const std::vector<std::uint32_t>& values, const std::string& product) {
  for (std::size_t i = 0; i < values.size(); ++i)
    set_default(require_entry(object, static_cast<std::uint8_t>(i + 1), product), values[i]);
  set_default(require_entry(object, 0, product), static_cast<std::uint32_t>(values.size()));
}

void apply_mapping(std::vector<ObjectDesc>& objects, const profile::PdoSpec& pdo,
                   const std::string& product) {
  // A PDO the dictionary has no mapping object for is an SII-only PDO: nothing to fill.
  ObjectDesc* object = find_object(objects, pdo.index);
  if (!object || !table_lists_nothing(*object) || pdo.entries.empty()) return;
  std::vector<std::uint32_t> values;
  for (const profile::PdoEntrySpec& e : pdo.entries)
    values.push_back(ecat::PdoMappingEntry::encode(e.index, e.subindex, static_cast<std::uint8_t>(e.bit_length)));
  fill(*object, values, product);
}

void apply_assignment(std::vector<ObjectDesc>& objects, std::uint16_t index, std::uint8_t sm,
                      const profile::ProductProfile& profile) {
  ObjectDesc* object = find_object(objects, index);
  if (!object || !table_lists_nothing(*object)) return;
  std::vector<std::uint32_t> assigned;
  for (const auto* list : {&profile.rx_pdos, &profile.tx_pdos})
    for (const profile::PdoSpec& pdo : *list)
      if (pdo.sync_manager == sm) assigned.push_back(pdo.index);
  if (!assigned.empty()) fill(*object, assigned, profile.id);
}

void add_sm_communication_types(std::vector<ObjectDesc>& objects,
                                const profile::ProductProfile& profile) {
  if (profile.sync_managers.empty()) return;
  std::vector<std::uint32_t> kinds;
  for (const profile::SyncManagerSpec& sm : profile.sync_managers)
    kinds.push_back(static_cast<std::uint32_t>(sm.kind));  // Kind values are ETG's codes
  if (ObjectDesc* existing = find_object(objects, 0x1C00)) {
    if (table_lists_nothing(*existing)) fill(*existing, kinds, profile.id);
    return;
  }
  ObjectDesc o;
  o.index = 0x1C00;
  o.name = "Sync manager communication type";
  o.code = ObjectCode::Array;
  auto entry = [&](std::uint8_t sub, std::string name, std::uint32_t value) {
    EntryDesc e;
    e.index = 0x1C00;
    e.subindex = sub;
    e.name = std::move(name);
    e.type = DataType::Unsigned8;
    e.bit_length = 8;
    e.value_bytes = 1;
    e.access = access::kReadAll;
    e.min = 0;
    e.max = sub == 0 ? static_cast<std::int64_t>(profile.sync_managers.size()) : 4;
    set_default(e, value);
    o.entries.push_back(std::move(e));
  };
  entry(0, "Number of used sync manager channels",
        static_cast<std::uint32_t>(profile.sync_managers.size()));
  for (std::size_t n = 0; n < kinds.size(); ++n)
    entry(static_cast<std::uint8_t>(n + 1), fmt::format("Communication type sync manager {}", n),
          kinds[n]);
  auto it = std::lower_bound(objects.begin(), objects.end(), std::uint16_t{0x1C00},
                             [](const ObjectDesc& x, std::uint16_t i) { return x.index < i; });
  objects.insert(it, std::move(o));
}

}  // namespace

void apply_default_pdo_configuration(std::vector<ObjectDesc>& objects,
                                     const profile::ProductProfile& profile) {
  for (const profile::PdoSpec& pdo : profile.rx_pdos) apply_mapping(objects, pdo, profile.id);
  for (const profile::PdoSpec& pdo : profile.tx_pdos) apply_mapping(objects, pdo, profile.id);
  apply_assignment(objects, 0x1C12, 2, profile);
  apply_assignment(objects, 0x1C13, 3, profile);
  add_sm_communication_types(objects, profile);
}

}  // namespace vdrive::od
