#include "vdrive/esi/esi_pdo_objects.hpp"

#include <algorithm>

#include "vdrive/esi/esi_dictionary_reader.hpp"

namespace vdrive::esi {
namespace {

using od::DataType;
using od::EntryDesc;
using od::ObjectDesc;

od::ObjectDesc* find(std::vector<ObjectDesc>& objects, std::uint16_t index) {
  for (ObjectDesc& o : objects)
    if (o.index == index) return &o;
  return nullptr;
}

EntryDesc make(std::uint16_t index, std::uint8_t sub, std::string name, DataType type, std::uint16_t bits,
               std::uint16_t access, std::uint64_t value) {
  EntryDesc e;
  e.index = index;
  e.subindex = sub;
  e.name = std::move(name);
  e.type = type;
  e.bit_length = bits;
  e.access = access;
  e.synthesized = true;
  e.value_bytes = std::max<std::uint32_t>(1, (bits + 7u) / 8u);
  e.default_value.assign(e.value_bytes, 0);
  for (std::size_t i = 0; i < e.default_value.size() && i < 8; ++i)
    e.default_value[i] = static_cast<std::uint8_t>(value >> (8 * i));
  return e;
}

// The type of a mapped entry: its DataType, else unsigned of its length.
od::DataType entry_type(const EsiPdoEntry& e) {
  if (const auto b = basic_type(e.data_type, e.bit_length)) return b->type;
  if (e.bit_length == 1) return DataType::Boolean;
  return e.bit_length <= 8 ? DataType::Unsigned8 : e.bit_length <= 16 ? DataType::Unsigned16
                           : e.bit_length <= 32 ? DataType::Unsigned32 : DataType::OctetString;
}

void add_mapped_entries(std::vector<ObjectDesc>& objects, const EsiPdo& pdo, bool outputs) {
  const std::uint16_t access = outputs ? (od::access::kReadAll | od::access::kWriteAll | od::access::kRxPdoMappable)
                                       : (od::access::kReadAll | od::access::kTxPdoMappable);
  for (const EsiPdoEntry& e : pdo.entries) {
    if (e.index == 0) continue;  // padding
    ObjectDesc* o = find(objects, e.index);
    if (o == nullptr) {
      objects.push_back(ObjectDesc{e.index, e.name, e.subindex == 0 ? od::ObjectCode::Var : od::ObjectCode::Record, {}});
      o = &objects.back();
    }
    if (o->entry(e.subindex) != nullptr) continue;
    o->entries.push_back(make(e.index, e.subindex, e.name, entry_type(e), e.bit_length, access, 0));
    if (e.subindex != 0) o->code = od::ObjectCode::Record;
    std::sort(o->entries.begin(), o->entries.end(), [](const EntryDesc& a, const EntryDesc& b) { return a.subindex < b.subindex; });
  }
  // A record's subindex 0 holds its highest subindex.
  for (ObjectDesc& o : objects) {
    if (o.code != od::ObjectCode::Record || o.entries.empty() || o.entries.front().subindex == 0) continue;
    o.entries.insert(o.entries.begin(), make(o.index, 0, "SubIndex 000", DataType::Unsigned8, 8, od::access::kReadAll,
                                             o.entries.back().subindex));
  }
}

// Writable in PreOp where the device lets a master configure its PDOs (CoE PdoConfig) and this
// one is not fixed, as ETG.1000.6 has it.
void add_mapping_object(std::vector<ObjectDesc>& objects, const EsiPdo& pdo, bool configurable) {
  if (find(objects, pdo.index) != nullptr) return;
  ObjectDesc o{pdo.index, pdo.name, od::ObjectCode::Array, {}};
  const auto n = static_cast<std::uint8_t>(std::min<std::size_t>(pdo.entries.size(), 254));
  const std::uint16_t access = configurable && !pdo.fixed ? (od::access::kReadAll | od::access::kWritePreOp)
                                                          : od::access::kReadAll;
  o.entries.push_back(make(pdo.index, 0, "SubIndex 000", DataType::Unsigned8, 8, access, n));
  for (std::uint8_t i = 0; i < n; ++i) {
    const EsiPdoEntry& e = pdo.entries[i];
    const std::uint64_t mapping = static_cast<std::uint64_t>(e.index) << 16 | static_cast<std::uint64_t>(e.subindex) << 8 |
                                  static_cast<std::uint8_t>(e.bit_length);
    o.entries.push_back(make(pdo.index, static_cast<std::uint8_t>(i + 1), "SubIndex " + std::to_string(i + 1),
                             DataType::Unsigned32, 32, access, mapping));
  }
  objects.push_back(std::move(o));
}

void add_assignment(std::vector<ObjectDesc>& objects, std::uint16_t index, const std::vector<EsiPdo>& pdos,
                    bool writable) {
  if (find(objects, index) != nullptr || pdos.empty()) return;
  std::vector<std::uint16_t> assigned;
  for (const EsiPdo& p : pdos)
    if (p.sm) assigned.push_back(p.index);
  const std::uint16_t access = writable ? (od::access::kReadAll | od::access::kWritePreOp) : od::access::kReadAll;
  ObjectDesc o{index, index == 0x1C12 ? "RxPDO assign" : "TxPDO assign", od::ObjectCode::Array, {}};
  o.entries.push_back(make(index, 0, "SubIndex 000", DataType::Unsigned8, 8, access, assigned.size()));
  const std::size_t n = std::min<std::size_t>(pdos.size(), 254);
  for (std::size_t i = 0; i < n; ++i)
    o.entries.push_back(make(index, static_cast<std::uint8_t>(i + 1), "SubIndex " + std::to_string(i + 1),
                             DataType::Unsigned16, 16, access, i < assigned.size() ? assigned[i] : 0));
  objects.push_back(std::move(o));
}

}  // namespace

void add_pdo_objects(std::vector<ObjectDesc>& objects, const EsiDevice& d) {
  for (const EsiPdo& p : d.rx_pdos) add_mapped_entries(objects, p, true);
  for (const EsiPdo& p : d.tx_pdos) add_mapped_entries(objects, p, false);
  for (const EsiPdo& p : d.rx_pdos) add_mapping_object(objects, p, d.pdo_config);
  for (const EsiPdo& p : d.tx_pdos) add_mapping_object(objects, p, d.pdo_config);
  add_assignment(objects, 0x1C12, d.rx_pdos, d.pdo_assign);
  add_assignment(objects, 0x1C13, d.tx_pdos, d.pdo_assign);
  std::sort(objects.begin(), objects.end(), [](const ObjectDesc& a, const ObjectDesc& b) { return a.index < b.index; });
}

}  // namespace vdrive::esi
