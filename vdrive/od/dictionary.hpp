#pragma once
// A product's object dictionary as a description: what objects and entries exist, their types,
// access, PDO mappability, defaults and limits. Immutable and shared by every slave of a product.
// Built from profiles/<id>/objects.yaml (embedded in the binary), or from an ESI file's dictionary,
// plus the identity in the ProductProfile (1000h, 1008h-100Ah, 1018h values come from the profile).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vdrive/od/data_type.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::od {

enum class ObjectCode : std::uint8_t { Var = 7, Array = 8, Record = 9 };

// ETG.1000.6 object access bits (SDO info entry description "ObjectAccess").
namespace access {
constexpr std::uint16_t kReadPreOp = 0x0001, kReadSafeOp = 0x0002, kReadOp = 0x0004;
constexpr std::uint16_t kWritePreOp = 0x0008, kWriteSafeOp = 0x0010, kWriteOp = 0x0020;
constexpr std::uint16_t kRxPdoMappable = 0x0040, kTxPdoMappable = 0x0080;
constexpr std::uint16_t kReadAll = kReadPreOp | kReadSafeOp | kReadOp;
constexpr std::uint16_t kWriteAll = kWritePreOp | kWriteSafeOp | kWriteOp;
}  // namespace access

// One hexadecimal digit field of a 16-bit parameter (DS5C1 `n.` parameters, objects.yaml
// attributes.fields): digits [shift/4, shift/4 + bits/4) hold a value that must lie in min..max.
struct DigitField {
  std::uint8_t shift = 0;   // bit position of the field's lowest digit
  std::uint8_t bits = 4;    // 4 per digit
  std::uint16_t min = 0, max = 0xF;
};

struct EntryDesc {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::string name;
  DataType type = DataType::Unsigned8;
  std::uint16_t bit_length = 8;        // strings: 8 * capacity
  std::uint16_t access = 0;            // access:: bits, incl. PDO mappability bits
  std::optional<std::int64_t> min, max;
  std::vector<DigitField> digit_fields;  // per-digit ranges; digits outside every field are free
  std::vector<std::uint8_t> default_value;  // little-endian, bit_length/8 bytes (min 1)
  std::string units;
  bool synthesized = false;            // not printed in the manual (e.g. sub 0 of a record)
  int manual_line = 0;
  std::uint32_t value_offset = 0;      // byte offset of this entry in an ObjectStore
  std::uint32_t value_bytes = 1;       // bytes it takes there: ceil(bit_length / 8), at least 1
};

struct ObjectDesc {
  std::uint16_t index = 0;
  std::string name;
  ObjectCode code = ObjectCode::Var;
  std::vector<EntryDesc> entries;      // sorted by subindex; may have gaps
  std::uint8_t max_subindex() const { return entries.empty() ? 0 : entries.back().subindex; }
  const EntryDesc* entry(std::uint8_t subindex) const;
};

class Dictionary {
public:
  // Loads the embedded objects.yaml of `profile.id` (or `<profile_dir>/<id>/objects.yaml`).
  // Throws profile::ProfileError naming the file, line and field on bad data.
  static Dictionary load(const profile::ProductProfile& profile, const std::string& profile_dir = {});
  // A dictionary of objects described elsewhere (an ESI file), completed as load() completes
  // objects.yaml: identity objects from the profile, and (with complete_pdo_objects) the PDO
  // objects the table leaves empty from the profile's default PDOs. Entries need value_bytes set.
  static Dictionary from_objects(std::vector<ObjectDesc> objects, const profile::ProductProfile& profile,
                                 bool complete_pdo_objects = true);

  const ObjectDesc* find(std::uint16_t index) const;                          // O(log n)
  const EntryDesc* find(std::uint16_t index, std::uint8_t subindex) const;
  std::span<const ObjectDesc> objects() const { return objects_; }             // sorted by index
  std::size_t entry_count() const;
  std::uint32_t value_bytes() const { return value_bytes_; }  // size of an ObjectStore's storage

private:
  std::vector<ObjectDesc> objects_;
  std::uint32_t value_bytes_ = 0;
};

}  // namespace vdrive::od
