#pragma once
// Reading a PDO mapping out of the object dictionary: the assignment object (1C12h/1C13h) names
// the mapping objects (16xxh/1Axxh), whose entries name the mapped objects as
// (index << 16) | (subindex << 8) | bit length. resolve() walks that chain, checks every step
// against the product's limits and the dictionary, and returns the mapped objects with their bit
// offsets in the process-data image. Runs at SDO writes and at PreOp->SafeOp, never cyclically;
// it allocates nothing (fixed tables).
#include <array>
#include <cstdint>
#include <string_view>

#include "ethercat/pdo_mapping_entry.hpp"
#include "vdrive/firmware/pdo/pdo_limits.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::firmware::pdo {

// Why a mapping is not usable, first failure found.
enum class MappingFault : std::uint8_t {
  Ok,
  BadAssignment,    // 1C1xh names no mapping object of this direction, or too many
  TooManyEntries,   // a mapping object's 00h exceeds the product's entries
  NoSuchObject,     // an entry names an object/subindex the dictionary does not have
  NotMappable,      // the object is not mappable in this direction
  WrongLength,      // the entry's bit length differs from the object's
  TooLong,          // the direction's PDOs together exceed the product's byte limit
};

std::string_view describe(MappingFault fault);

// Checks one mapping entry for `direction`; on success `out` is the mapped entry (null for a gap).
MappingFault check_entry(const od::Dictionary& dictionary, ecat::PdoMappingEntry entry, Direction direction,
                         const od::EntryDesc*& out);

// An unsigned value (up to 32 bits, little-endian) from the store; 0 if the entry does not exist.
std::uint32_t read_unsigned(const od::ObjectStore& objects, std::uint16_t index,
                            std::uint8_t subindex);

struct MappedItem {
  const od::EntryDesc* entry = nullptr;  // null: a gap
  std::uint32_t bit_offset = 0;          // in the direction's process-data image
  std::uint16_t bits = 0;
};

struct ResolvedMapping {
  std::array<MappedItem, kMaxMappedEntries> items{};
  int count = 0;
  std::uint32_t bits = 0;
  MappingFault fault = MappingFault::Ok;

  std::uint16_t bytes() const { return static_cast<std::uint16_t>((bits + 7) / 8); }
  bool ok() const { return fault == MappingFault::Ok; }
};

// The mapping currently assigned to the direction's SyncManager (1C12h for Rx, 1C13h for Tx).
void resolve(const od::ObjectStore& objects, Direction direction, const DirectionLimits& limits,
             ResolvedMapping& out);

// The entries of one mapping object as if its 00h were `count` (used to judge a 00h write
// before it is stored). Appends to `out` starting at out.bits.
MappingFault append_mapping_object(const od::ObjectStore& objects, std::uint16_t mapping_index,
                                   std::uint8_t count, Direction direction,
                                   const DirectionLimits& limits, ResolvedMapping& out);

}  // namespace vdrive::firmware::pdo
