#include "vdrive/od/identity_objects.hpp"

#include <algorithm>
#include <string>

#include "ethercat/little_endian.hpp"

namespace vdrive::od {

namespace {

ObjectDesc& object_at(std::vector<ObjectDesc>& objects, std::uint16_t index, std::string_view name,
                      ObjectCode code) {
  auto it = std::lower_bound(objects.begin(), objects.end(), index,
                             [](const ObjectDesc& o, std::uint16_t i) { return o.index < i; });
  if (it != objects.end() && it->index == index) return *it;
  ObjectDesc o;
  o.index = index;
  o.name = std::string(name);
  o.code = code;
  return *objects.insert(it, std::move(o));
}

EntryDesc& entry_at(ObjectDesc& object, std::uint8_t subindex, std::string_view name, DataType type) {
  auto it = std::lower_bound(object.entries.begin(), object.entries.end(), subindex,
                             [](const EntryDesc& e, std::uint8_t s) { return e.subindex < s; });
  if (it != object.entries.end() && it->subindex == subindex) return *it;
  EntryDesc e;
  e.index = object.index;
  e.subindex = subindex;
  e.name = std::string(name);
  e.type = type;
  e.bit_length = fixed_bit_size(type);
  e.value_bytes = std::max<std::uint32_t>(1, (e.bit_length + 7u) / 8u);
  e.access = access::kReadAll;   // identity is read-only in every product
  e.synthesized = true;
  if (!is_string(type)) {
    e.min = 0;
    e.max = type == DataType::Unsigned8 ? 0xFF : 0xFFFFFFFF;
  }
  return *object.entries.insert(it, std::move(e));
}

void set_u32(EntryDesc& e, std::uint32_t value) {
  e.default_value.assign(e.value_bytes, 0);
  ecat::put_le(std::span(e.default_value).first(std::min<std::size_t>(e.default_value.size(), 4)), value);
}

// A string entry sized to exactly the profile's text, so a read returns just that text.
void set_string(EntryDesc& e, const std::string& text) {
  const std::size_t bytes = std::max<std::size_t>(text.size(), 1);
  e.bit_length = static_cast<std::uint16_t>(8 * bytes);
  e.value_bytes = static_cast<std::uint32_t>(bytes);
  e.default_value.assign(bytes, 0);
  std::copy(text.begin(), text.end(), e.default_value.begin());
}

void string_object(std::vector<ObjectDesc>& objects, std::uint16_t index, std::string_view name,
                   const std::string& value) {
  ObjectDesc& o = object_at(objects, index, name, ObjectCode::Var);
  set_string(entry_at(o, 0, name, DataType::VisibleString), value);
}

}  // namespace

void apply_identity(std::vector<ObjectDesc>& objects, const profile::Identity& id) {
  {
    ObjectDesc& o = object_at(objects, 0x1000, "Device type", ObjectCode::Var);
    set_u32(entry_at(o, 0, "Device type", DataType::Unsigned32), id.device_type);
  }
  string_object(objects, 0x1008, "Manufacturer device name", id.device_name);
  string_object(objects, 0x1009, "Manufacturer hardware version", id.hardware_version);
  string_object(objects, 0x100A, "Manufacturer software version", id.software_version);

  ObjectDesc& o = object_at(objects, 0x1018, "Identity object", ObjectCode::Record);
  entry_at(o, 0, "Number of entries", DataType::Unsigned8);
  set_u32(entry_at(o, 1, "Vendor ID", DataType::Unsigned32), id.vendor_id);
  set_u32(entry_at(o, 2, "Product code", DataType::Unsigned32), id.product_code);
  set_u32(entry_at(o, 3, "Revision number", DataType::Unsigned32), id.revision);
  set_u32(entry_at(o, 4, "Serial number", DataType::Unsigned32), id.serial);
  // Subindex 0 counts the entries (looked up again: the inserts may have moved it).
  EntryDesc& sub0 = o.entries.front();
  const std::uint8_t highest = o.max_subindex();
  set_u32(sub0, highest);
  if (sub0.max && *sub0.max < highest) sub0.max = highest;
  if (sub0.min && *sub0.min > highest) sub0.min = highest;
}

}  // namespace vdrive::od
