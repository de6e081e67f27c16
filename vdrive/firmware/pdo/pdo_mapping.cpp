#include "vdrive/firmware/pdo/pdo_mapping.hpp"

#include <algorithm>

#include "ethercat/little_endian.hpp"

namespace vdrive::firmware::pdo {

std::string_view describe(MappingFault fault) {
  switch (fault) {
    case MappingFault::Ok: return "ok";
    case MappingFault::BadAssignment: return "assignment names no usable mapping object";
    case MappingFault::TooManyEntries: return "mapping object has more entries than the product allows";
    case MappingFault::NoSuchObject: return "mapped object does not exist";
    case MappingFault::NotMappable: return "object is not mappable in this direction";
    case MappingFault::WrongLength: return "mapped bit length differs from the object's";
    case MappingFault::TooLong: return "mapped data exceeds the product's PDO size";
  }
  return "?";
}

MappingFault check_entry(const od::Dictionary& dictionary, ecat::PdoMappingEntry entry, Direction direction,
                         const od::EntryDesc*& out) {
  out = nullptr;
  if (entry.bits == 0) return MappingFault::NoSuchObject;  // an unused (zero) entry maps nothing
  if (entry.is_gap()) return MappingFault::Ok;
  const od::EntryDesc* desc = dictionary.find(entry.index, entry.subindex);
  if (desc == nullptr) return MappingFault::NoSuchObject;
  const std::uint16_t mappable =
      direction == Direction::Rx ? od::access::kRxPdoMappable : od::access::kTxPdoMappable;
  if ((desc->access & mappable) == 0) return MappingFault::NotMappable;
  if (desc->bit_length != entry.bits) return MappingFault::WrongLength;
  out = desc;
  return MappingFault::Ok;
}

std::uint32_t read_unsigned(const od::ObjectStore& objects, std::uint16_t index,
                            std::uint8_t subindex) {
  const od::EntryDesc* desc = objects.dictionary().find(index, subindex);
  if (desc == nullptr) return 0;
  const std::span<const std::uint8_t> bytes = objects.raw(*desc);
  return static_cast<std::uint32_t>(ecat::get_le(bytes.first(std::min<std::size_t>(bytes.size(), 4))));
}

MappingFault append_mapping_object(const od::ObjectStore& objects, std::uint16_t mapping_index,
                                   std::uint8_t count, Direction direction,
                                   const DirectionLimits& limits, ResolvedMapping& out) {
  if (count > limits.max_entries || count > kMaxEntriesPerPdo) return MappingFault::TooManyEntries;
  for (std::uint8_t sub = 1; sub <= count; ++sub) {
    const ecat::PdoMappingEntry entry =
        ecat::PdoMappingEntry::decode(read_unsigned(objects, mapping_index, sub));
    const od::EntryDesc* desc = nullptr;
    const MappingFault fault = check_entry(objects.dictionary(), entry, direction, desc);
    if (fault != MappingFault::Ok) return fault;
    if (out.count >= kMaxMappedEntries) return MappingFault::TooManyEntries;
    out.items[static_cast<std::size_t>(out.count++)] = MappedItem{desc, out.bits, entry.bits};
    out.bits += entry.bits;
    if (out.bits > static_cast<std::uint32_t>(limits.max_bytes) * 8) return MappingFault::TooLong;
  }
  return MappingFault::Ok;
}

void resolve(const od::ObjectStore& objects, Direction direction, const DirectionLimits& limits,
             ResolvedMapping& out) {
  out.count = 0;
  out.bits = 0;
  out.fault = MappingFault::Ok;
  const std::uint16_t assign = direction == Direction::Rx ? kRxAssign : kTxAssign;
  const std::uint32_t assigned = read_unsigned(objects, assign, 0);
  if (assigned > limits.max_assigned || assigned > kMaxAssigned) {
    out.fault = MappingFault::BadAssignment;
    return;
  }
  for (std::uint32_t k = 1; k <= assigned; ++k) {
    const auto mapping = static_cast<std::uint16_t>(
        read_unsigned(objects, assign, static_cast<std::uint8_t>(k)));
    if (!limits.is_mapping_object(mapping) || objects.dictionary().find(mapping) == nullptr) {
      out.fault = MappingFault::BadAssignment;
      return;
    }
    const auto count = static_cast<std::uint8_t>(read_unsigned(objects, mapping, 0));
    out.fault = append_mapping_object(objects, mapping, count, direction, limits, out);
    if (out.fault != MappingFault::Ok) return;
  }
}

}  // namespace vdrive::firmware::pdo
