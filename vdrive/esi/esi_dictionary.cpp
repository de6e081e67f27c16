#include "vdrive/esi/esi_dictionary.hpp"

#include <fmt/core.h>

#include <map>
#include <vector>

#include "ethercat/little_endian.hpp"
#include "vdrive/esi/esi_names.hpp"

namespace vdrive::esi {
namespace {

using od::EntryDesc;
using od::ObjectDesc;

// Access state sets as ETG.2000 spells them: bit0 PreOP, bit1 SafeOP, bit2 OP.
std::string restriction(unsigned states) {
  switch (states & 0x7) {
    case 1: return "PreOP";
    case 2: return "SafeOP";
    case 4: return "OP";
    case 3: return "PreOP_SafeOP";
    case 5: return "PreOP_OP";
    case 6: return "SafeOP_OP";
    default: return {};  // 7: every state (no restriction); 0 handled by the caller
  }
}

std::string entry_type(const EntryDesc& e) { return type_name(e.type, e.bit_length); }

bool is_complex(const ObjectDesc& o) { return o.code != od::ObjectCode::Var; }

std::string complex_type_name(const ObjectDesc& o) { return fmt::format("DT{:04X}", o.index); }

// An ARRAY written the ETG way: subindex 0, then one element array (ArrayInfo) of subindexes 1..n,
// every element of one type, size and access; that is how a reader tells an ARRAY from a RECORD.
// An ARRAY that is not so regular is written as a record of its entries.
bool etg_array(const ObjectDesc& o) {
  if (o.code != od::ObjectCode::Array || o.entries.size() < 2 || o.entries[0].subindex != 0) return false;
  const EntryDesc& first = o.entries[1];
  for (std::size_t i = 1; i < o.entries.size(); ++i) {
    const EntryDesc& e = o.entries[i];
    if (e.subindex != i || e.type != first.type || e.bit_length != first.bit_length || e.access != first.access)
      return false;
  }
  return true;
}

// Bit offsets for the complex type's SubItems, as a complete access transfers them: subindex 0
// padded to 16 bits, the other entries packed in subindex order.
struct Layout {
  std::vector<std::uint32_t> offsets;  // per entry, in entries order
  std::uint32_t bit_size = 0;
};
Layout layout(const ObjectDesc& o) {
  Layout l;
  std::uint32_t offset = 0;
  for (const EntryDesc& e : o.entries) {
    l.offsets.push_back(offset);
    offset += e.subindex == 0 ? 16 : e.bit_length;
  }
  l.bit_size = offset;
  return l;
}

// Little-endian bytes of a limit, as wide as the entry (at least one byte).
std::vector<std::uint8_t> limit_bytes(std::int64_t value, std::uint16_t bit_length) {
  const std::size_t n = std::max<std::size_t>(1, (bit_length + 7u) / 8u);
  std::vector<std::uint8_t> out(n);
  ecat::put_le(out, static_cast<std::uint64_t>(value));
  return out;
}

// <Info> of a single value: MinData, MaxData, DefaultData (hex, little-endian), or DefaultString
// for a visible string. With `always` an empty <Info/> is written when the dictionary knows none
// of them (a SubItem of an object's Info must have one).
void write_value_info(XmlWriter& xml, const EntryDesc& e, bool always) {
  const bool numeric = e.type != od::DataType::VisibleString && e.type != od::DataType::OctetString;
  const bool has_limits = numeric && (e.min || e.max);
  std::string text;
  if (e.type == od::DataType::VisibleString) {
    text.assign(e.default_value.begin(), e.default_value.end());
    while (!text.empty() && text.back() == '\0') text.pop_back();
  }
  const bool has_default = e.type == od::DataType::VisibleString ? !text.empty() : !e.default_value.empty();
  if (!has_limits && !has_default && !always) return;
  xml.open("Info");
  if (e.type == od::DataType::VisibleString) {
    if (has_default) xml.element("DefaultString", text);
  } else {
    if (has_limits && e.min) xml.element("MinData", hex_binary(limit_bytes(*e.min, e.bit_length)));
    if (has_limits && e.max) xml.element("MaxData", hex_binary(limit_bytes(*e.max, e.bit_length)));
    if (has_default) xml.element("DefaultData", hex_binary(e.default_value));
  }
  xml.close();
}

// SubItem names must be unique within a type (schema key SubItemKey); manuals repeat names such
// as "For manufacturer's use", so a repeated name gets its subindex appended.
std::vector<std::string> subitem_names(const ObjectDesc& o) {
  std::map<std::string, int> uses;
  for (const EntryDesc& e : o.entries) ++uses[e.name];
  std::vector<std::string> names;
  for (const EntryDesc& e : o.entries)
    names.push_back(uses[e.name] > 1 || e.name.empty() ? fmt::format("{} (sub {:02X}h)", e.name, e.subindex) : e.name);
  return names;
}

void write_flags(XmlWriter& xml, const EntryDesc& e) {
  const AccessText a = access_text(e.access);
  const std::string mapping = pdo_mapping_text(e.access);
  // The manual prints "-" for reserved/manufacturer entries: no Access is claimed for them.
  if (a.access.empty() && mapping.empty()) return;
  xml.open("Flags");
  if (!a.access.empty()) {
    xml.open("Access");
    if (!a.read_restrictions.empty()) xml.attr("ReadRestrictions", a.read_restrictions);
    if (!a.write_restrictions.empty()) xml.attr("WriteRestrictions", a.write_restrictions);
    xml.close_with_text(a.access);
  }
  if (!mapping.empty()) xml.element("PdoMapping", mapping);
  xml.close();
}

void write_data_types(XmlWriter& xml, const od::Dictionary& d) {
  // Every basic type an entry uses, once, sorted by name (deterministic output).
  std::map<std::string, std::uint16_t> basic;
  for (const ObjectDesc& o : d.objects())
    for (const EntryDesc& e : o.entries) basic.emplace(entry_type(e), e.bit_length);
  basic.erase("");
  xml.open("DataTypes");
  for (const auto& [name, bits] : basic) {
    xml.open("DataType");
    xml.element("Name", name);
    xml.element("BitSize", std::to_string(bits));
    xml.close();
  }
  for (const ObjectDesc& o : d.objects()) {
    if (!is_complex(o)) continue;
    const Layout l = layout(o);
    const std::vector<std::string> names = subitem_names(o);
    if (etg_array(o)) {
      const EntryDesc& sub0 = o.entries[0];
      const EntryDesc& element = o.entries[1];
      const std::size_t n = o.entries.size() - 1;
      const std::string array_type = complex_type_name(o) + "ARR";
      xml.open("DataType");
      xml.element("Name", array_type);
      xml.element("BaseType", entry_type(element));
      xml.element("BitSize", std::to_string(n * element.bit_length));
      xml.open("ArrayInfo");
      xml.element("LBound", "1");
      xml.element("Elements", std::to_string(n));
      xml.close();
      xml.close();
      xml.open("DataType");
      xml.element("Name", complex_type_name(o));
      xml.element("BitSize", std::to_string(l.bit_size));
      xml.open("SubItem");
      xml.element("SubIdx", "0");
      xml.element("Name", names[0]);
      xml.element("Type", entry_type(sub0));
      xml.element("BitSize", std::to_string(sub0.bit_length));
      xml.element("BitOffs", "0");
      write_flags(xml, sub0);
      xml.close();
      xml.open("SubItem");
      xml.element("Name", "Elements");
      xml.element("Type", array_type);
      xml.element("BitSize", std::to_string(n * element.bit_length));
      xml.element("BitOffs", "16");
      write_flags(xml, element);
      xml.close();
      xml.close();
      continue;
    }
    xml.open("DataType");
    xml.element("Name", complex_type_name(o));
    xml.element("BitSize", std::to_string(l.bit_size));
    for (std::size_t i = 0; i < o.entries.size(); ++i) {
      const EntryDesc& e = o.entries[i];
      xml.open("SubItem");
      xml.element("SubIdx", std::to_string(e.subindex));
      xml.element("Name", names[i]);
      xml.element("Type", entry_type(e));
      xml.element("BitSize", std::to_string(e.bit_length));
      xml.element("BitOffs", std::to_string(l.offsets[i]));
      write_flags(xml, e);
      xml.close();
    }
    xml.close();
  }
  xml.close();
}

void write_object(XmlWriter& xml, const ObjectDesc& o) {
  if (o.entries.empty()) return;  // nothing a master could address
  xml.open("Object");
  xml.element("Index", hex(o.index, 4));
  xml.element("Name", o.name);
  if (!is_complex(o)) {
    const EntryDesc& e = o.entries.front();
    xml.element("Type", entry_type(e));
    xml.element("BitSize", std::to_string(e.bit_length));
    write_value_info(xml, e, false);
    write_flags(xml, e);
  } else {
    xml.element("Type", complex_type_name(o));
    xml.element("BitSize", std::to_string(layout(o).bit_size));
    // One SubItem per entry, in DataType SubItem order, each with its own values.
    const std::vector<std::string> names = subitem_names(o);
    xml.open("Info");
    for (std::size_t i = 0; i < o.entries.size(); ++i) {
      xml.open("SubItem");
      xml.element("Name", names[i]);
      write_value_info(xml, o.entries[i], true);
      xml.close();
    }
    xml.close();
  }
  xml.close();
}

}  // namespace

AccessText access_text(std::uint16_t bits) {
  const unsigned read = bits & od::access::kReadAll;
  const unsigned write = (bits & od::access::kWriteAll) >> 3;
  AccessText t;
  if (read == 0 && write == 0) return t;
  t.access = write == 0 ? "ro" : read == 0 ? "wo" : "rw";
  if (read != 0) t.read_restrictions = restriction(read);
  if (write != 0) t.write_restrictions = restriction(write);
  return t;
}

std::string pdo_mapping_text(std::uint16_t bits) {
  std::string m;
  if (bits & od::access::kRxPdoMappable) m += 'R';
  if (bits & od::access::kTxPdoMappable) m += 'T';
  return m;
}

void write_dictionary(XmlWriter& xml, const od::Dictionary& d) {
  xml.open("Dictionary");
  write_data_types(xml, d);
  xml.open("Objects");
  for (const ObjectDesc& o : d.objects()) write_object(xml, o);
  xml.close();
  xml.close();
}

}  // namespace vdrive::esi
