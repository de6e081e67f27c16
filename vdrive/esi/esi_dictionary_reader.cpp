#include "vdrive/esi/esi_dictionary_reader.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <map>
#include <string>

#include "ethercat/little_endian.hpp"

namespace vdrive::esi {
namespace {

using od::DataType;
using od::EntryDesc;
using od::ObjectDesc;
using tinyxml2::XMLElement;

struct Flags {
  bool present = false;
  std::uint16_t access = 0;  // od::access bits
};

struct SubItemDef {
  std::optional<std::uint8_t> subindex;
  std::string name, type;
  std::uint32_t bit_size = 0;
  Flags flags;
  const XMLElement* at = nullptr;
};

struct TypeDef {
  std::string base_type;
  std::uint32_t bit_size = 0;
  bool array = false;
  std::int64_t lower_bound = 0, elements = 0;
  std::vector<SubItemDef> sub_items;
  const XMLElement* at = nullptr;
};

// "PreOP", "PreOP_SafeOP", "SafeOP_OP", "OP", ... -> state bits PreOp 1, SafeOp 2, Op 4.
unsigned states(const XmlReading& xml, const XMLElement* e, const char* attribute) {
  const char* v = e->Attribute(attribute);
  if (v == nullptr) return 0x7;
  const std::string_view s(v);
  unsigned bits = 0;
  std::size_t from = 0;
  while (from <= s.size()) {
    const std::size_t to = std::min(s.find('_', from), s.size());
    const std::string_view part = s.substr(from, to - from);
    if (part == "PreOP") bits |= 1;
    else if (part == "SafeOP") bits |= 2;
    else if (part == "OP") bits |= 4;
    else xml.fail(e, fmt::format("{} '{}': expected PreOP, SafeOP, OP joined by _", attribute, s));
    from = to + 1;
  }
  return bits;
}

Flags read_flags(const XmlReading& xml, const XMLElement* flags) {
  Flags f;
  if (flags == nullptr) return f;
  f.present = true;
  if (const XMLElement* access = XmlReading::child(flags, "Access")) {
    const std::string a = XmlReading::text(access);
    const bool read = a == "ro" || a == "rw";
    const bool write = a == "rw" || a == "wo";
    if (!read && !write) xml.fail(access, fmt::format("'{}': expected ro, rw or wo", a));
    if (read) f.access |= static_cast<std::uint16_t>(states(xml, access, "ReadRestrictions"));
    if (write) f.access |= static_cast<std::uint16_t>(states(xml, access, "WriteRestrictions") << 3);
  }
  if (const XMLElement* mapping = XmlReading::child(flags, "PdoMapping")) {
    for (const char c : XmlReading::text(mapping)) {
      if (c == 'R' || c == 'r') f.access |= od::access::kRxPdoMappable;
      else if (c == 'T' || c == 't') f.access |= od::access::kTxPdoMappable;
      else xml.fail(mapping, fmt::format("'{}': expected R, T or RT", XmlReading::text(mapping)));
    }
  }
  return f;
}

// A name with its length in brackets ("STRING(16)") -> 16; nullopt otherwise.
std::optional<std::uint32_t> bracketed(std::string_view name, std::string_view prefix) {
  if (name.size() < prefix.size() + 3 || name.substr(0, prefix.size()) != prefix || name[prefix.size()] != '(' ||
      name.back() != ')')
    return std::nullopt;
  const std::string_view digits = name.substr(prefix.size() + 1, name.size() - prefix.size() - 2);
  std::uint32_t n = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return n;
}

std::uint16_t clamp_bits(std::uint32_t bits) { return static_cast<std::uint16_t>(std::min<std::uint32_t>(bits, 0xFFF8)); }

// Little-endian bytes of `value`, `n` bytes long.
std::vector<std::uint8_t> le_bytes(std::int64_t value, std::size_t n) {
  std::vector<std::uint8_t> out(n);
  for (std::size_t i = 0; i < n && i < 8; ++i) out[i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i));
  return out;
}

// A limit from hexBinary (little-endian, as wide as the entry), sign-extended for signed types.
std::int64_t from_le(const std::vector<std::uint8_t>& bytes, const EntryDesc& e) {
  const std::size_t n = std::min<std::size_t>(bytes.size(), 8);
  std::uint64_t u = 0;
  for (std::size_t i = 0; i < n; ++i) u |= static_cast<std::uint64_t>(bytes[i]) << (8 * i);
  const unsigned bits = static_cast<unsigned>(std::min<std::size_t>(n * 8, e.bit_length));
  if (od::is_signed(e.type) && bits > 0 && bits < 64 && ((u >> (bits - 1)) & 1u)) u |= ~0ull << bits;
  if (bits > 0 && bits < 64 && !od::is_signed(e.type)) u &= (1ull << bits) - 1;
  return static_cast<std::int64_t>(u);
}

// The values of one entry from an <Info> (object or SubItem).
void read_values(const XmlReading& xml, const XMLElement* info, EntryDesc& e) {
  if (info == nullptr) return;
  if (od::is_string(e.type)) {
    if (const XMLElement* s = XmlReading::child(info, "DefaultString")) {
      const std::string text = XmlReading::text(s);
      std::copy_n(text.begin(), std::min(text.size(), e.default_value.size()), e.default_value.begin());
    } else if (const XMLElement* d = XmlReading::child(info, "DefaultData")) {
      const std::vector<std::uint8_t> bytes = xml.hex_binary(d);
      std::copy_n(bytes.begin(), std::min(bytes.size(), e.default_value.size()), e.default_value.begin());
    }
    return;
  }
  // Floats and 64-bit unsigned values keep their bytes; a range of them is not a signed 64-bit one.
  const bool ranged = e.type != DataType::Real32 && e.type != DataType::Unsigned64;
  constexpr std::int64_t kLo = std::numeric_limits<std::int64_t>::min(), kHi = std::numeric_limits<std::int64_t>::max();
  if (const XMLElement* d = XmlReading::child(info, "DefaultData")) {
    const std::vector<std::uint8_t> bytes = xml.hex_binary(d);
    std::fill(e.default_value.begin(), e.default_value.end(), 0);
    std::copy_n(bytes.begin(), std::min(bytes.size(), e.default_value.size()), e.default_value.begin());
  } else if (const XMLElement* v = XmlReading::child(info, "DefaultValue")) {
    e.default_value = le_bytes(xml.number(v, kLo, kHi), e.value_bytes);
  }
  if (!ranged) return;
  if (const XMLElement* m = XmlReading::child(info, "MinData")) e.min = from_le(xml.hex_binary(m), e);
  else if (const XMLElement* v = XmlReading::child(info, "MinValue")) e.min = xml.number(v, kLo, kHi);
  if (const XMLElement* m = XmlReading::child(info, "MaxData")) e.max = from_le(xml.hex_binary(m), e);
  else if (const XMLElement* v = XmlReading::child(info, "MaxValue")) e.max = xml.number(v, kLo, kHi);
}

// A SubItem name the exporter made unique (" (sub 0Ch)" for subindex 0Ch) gets its manual name back.
std::string unique_name_undone(const std::string& name, std::uint8_t subindex) {
  const std::string suffix = fmt::format(" (sub {:02X}h)", subindex);
  if (name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
    return name.substr(0, name.size() - suffix.size());
  return name;
}

class DictionaryReader {
public:
  explicit DictionaryReader(const XmlReading& xml) : xml_(xml) {}

  std::vector<ObjectDesc> read(const XMLElement* dictionary) {
    if (const XMLElement* types = XmlReading::child(dictionary, "DataTypes"))
      for (const XMLElement* t = types->FirstChildElement("DataType"); t; t = t->NextSiblingElement("DataType"))
        read_type(t);
    std::vector<ObjectDesc> objects;
    const XMLElement* list = xml_.required(dictionary, "Objects");
    for (const XMLElement* o = list->FirstChildElement("Object"); o; o = o->NextSiblingElement("Object")) {
      ObjectDesc desc = read_object(o);
      for (const ObjectDesc& seen : objects)
        if (seen.index == desc.index) xml_.fail(o, fmt::format("object {:04X}h is described twice", desc.index));
      objects.push_back(std::move(desc));
    }
    std::sort(objects.begin(), objects.end(), [](const ObjectDesc& a, const ObjectDesc& b) { return a.index < b.index; });
    return objects;
  }

private:
  void read_type(const XMLElement* t) {
    TypeDef def;
    def.at = t;
    const std::string name = XmlReading::text(xml_.required(t, "Name"));
    def.base_type = XmlReading::text(XmlReading::child(t, "BaseType"));
    def.bit_size = static_cast<std::uint32_t>(xml_.number(xml_.required(t, "BitSize"), 0, 0xFFFFFF));
    if (const XMLElement* a = XmlReading::child(t, "ArrayInfo")) {
      def.array = true;
      def.lower_bound = xml_.optional_number(a, "LBound", 0, 255).value_or(0);
      def.elements = xml_.number(xml_.required(a, "Elements"), 0, 0xFFFF);
    }
    for (const XMLElement* s = t->FirstChildElement("SubItem"); s; s = s->NextSiblingElement("SubItem")) {
      SubItemDef sub;
      sub.at = s;
      if (const auto idx = xml_.optional_number(s, "SubIdx", 0, 255)) sub.subindex = static_cast<std::uint8_t>(*idx);
      sub.name = XmlReading::text(xml_.required(s, "Name"));
      sub.type = XmlReading::text(xml_.required(s, "Type"));
      sub.bit_size = static_cast<std::uint32_t>(xml_.number(xml_.required(s, "BitSize"), 0, 0xFFFFFF));
      sub.flags = read_flags(xml_, XmlReading::child(s, "Flags"));
      def.sub_items.push_back(std::move(sub));
    }
    types_[name] = std::move(def);
  }

  // A basic type by name, through BaseType aliases and byte arrays.
  std::optional<BasicType> resolve_basic(const std::string& name, std::uint32_t bits, int depth = 0) const {
    if (const auto b = basic_type(name, bits)) return b;
    const auto it = types_.find(name);
    if (it == types_.end() || depth > 8 || !it->second.sub_items.empty()) return std::nullopt;
    const TypeDef& def = it->second;
    if (def.array) {
      const auto element = resolve_basic(def.base_type, def.elements > 0 ? def.bit_size / def.elements : 8, depth + 1);
      // An array of bytes or characters in one entry is an octet or visible string.
      if (element && element->bits == 8 && !od::is_signed(element->type))
        return BasicType{element->type == DataType::VisibleString ? DataType::VisibleString : DataType::OctetString,
                         clamp_bits(bits)};
      return std::nullopt;
    }
    if (!def.base_type.empty()) return resolve_basic(def.base_type, bits, depth + 1);
    return std::nullopt;
  }

  EntryDesc make_entry(const XMLElement* at, std::uint16_t index, std::uint8_t subindex, std::string name,
                       const std::string& type, std::uint32_t bits, const Flags& own, const Flags& object) const {
    const std::optional<BasicType> basic = resolve_basic(type, bits);
    if (!basic) xml_.fail(at, fmt::format("object {:04X}h sub {}: type '{}' is not a basic type or a type this file "
                                          "defines", index, subindex, type));
    EntryDesc e;
    e.index = index;
    e.subindex = subindex;
    e.name = std::move(name);
    e.type = basic->type;
    e.bit_length = basic->bits;
    // No Flags of its own: the object's; none at all: no access is claimed (as written).
    e.access = own.present ? own.access : object.access;
    e.value_bytes = std::max<std::uint32_t>(1, (e.bit_length + 7u) / 8u);
    e.default_value.assign(e.value_bytes, 0);
    return e;
  }

  ObjectDesc read_object(const XMLElement* o) {
    ObjectDesc desc;
    desc.index = static_cast<std::uint16_t>(xml_.number(xml_.required(o, "Index"), 0, 0xFFFF));
    desc.name = XmlReading::english(o, "Name");
    const std::string type = XmlReading::text(xml_.required(o, "Type"));
    const auto bits = static_cast<std::uint32_t>(xml_.number(xml_.required(o, "BitSize"), 0, 0xFFFFFF));
    const Flags flags = read_flags(xml_, XmlReading::child(o, "Flags"));
    const XMLElement* info = XmlReading::child(o, "Info");

    const auto it = types_.find(type);
    if (it == types_.end() || it->second.sub_items.empty()) {
      desc.code = od::ObjectCode::Var;
      EntryDesc e = make_entry(o, desc.index, 0, desc.name, type, bits, Flags{}, flags);
      read_values(xml_, info, e);
      desc.entries.push_back(std::move(e));
      return desc;
    }
    desc.code = od::ObjectCode::Record;
    // The entries the type lays out, in order; an element array expands into one entry per element.
    for (const SubItemDef& sub : it->second.sub_items) {
      const auto element = types_.find(sub.type);
      // An element array expands into its elements; a SubItem with its own SubIdx whose type is a
      // byte array ("ARRAY [0..511] OF BYTE") is one entry, an octet string.
      const bool one_entry = sub.subindex.has_value() && resolve_basic(sub.type, sub.bit_size).has_value();
      if (!one_entry && element != types_.end() && element->second.array && element->second.sub_items.empty()) {
        const TypeDef& arr = element->second;
        desc.code = od::ObjectCode::Array;
        const std::uint32_t element_bits = arr.elements > 0 ? arr.bit_size / static_cast<std::uint32_t>(arr.elements) : 0;
        const std::int64_t first = sub.subindex.value_or(static_cast<std::uint8_t>(arr.lower_bound));
        for (std::int64_t k = 0; k < arr.elements; ++k) {
          const std::int64_t subindex = first + k;
          if (subindex > 255) xml_.fail(sub.at, fmt::format("object {:04X}h: array reaches past subindex 255", desc.index));
          desc.entries.push_back(make_entry(sub.at, desc.index, static_cast<std::uint8_t>(subindex),
                                            fmt::format("SubIndex {:03}", subindex), arr.base_type, element_bits,
                                            sub.flags, flags));
        }
        continue;
      }
      if (!sub.subindex) xml_.fail(sub.at, fmt::format("object {:04X}h: SubItem '{}' has no SubIdx", desc.index, sub.name));
      desc.entries.push_back(make_entry(sub.at, desc.index, *sub.subindex, unique_name_undone(sub.name, *sub.subindex),
                                        sub.type, sub.bit_size, sub.flags, flags));
    }
    std::sort(desc.entries.begin(), desc.entries.end(),
              [](const EntryDesc& a, const EntryDesc& b) { return a.subindex < b.subindex; });
    for (std::size_t i = 1; i < desc.entries.size(); ++i)
      if (desc.entries[i].subindex == desc.entries[i - 1].subindex)
        xml_.fail(o, fmt::format("object {:04X}h: subindex {} is described twice", desc.index, desc.entries[i].subindex));
    read_sub_item_values(info, it->second.sub_items, desc);
    return desc;
  }

  // Object <Info><SubItem><Name>..</Name><Info>..</Info></SubItem>: matched to the type's SubItems
  // by name; where the names are the array's "SubIndex 001" or differ, by position.
  void read_sub_item_values(const XMLElement* info, const std::vector<SubItemDef>& subs, ObjectDesc& desc) const {
    if (info == nullptr) return;
    std::size_t position = 0;
    for (const XMLElement* s = info->FirstChildElement("SubItem"); s; s = s->NextSiblingElement("SubItem"), ++position) {
      const std::string name = XmlReading::text(XmlReading::child(s, "Name"));
      EntryDesc* target = nullptr;
      for (const SubItemDef& sub : subs)
        if (sub.name == name && sub.subindex)
          for (EntryDesc& e : desc.entries)
            if (e.subindex == *sub.subindex) target = &e;
      if (target == nullptr)
        for (EntryDesc& e : desc.entries)
          if (e.name == name) target = &e;
      if (target == nullptr && position < desc.entries.size()) {
        target = &desc.entries[position];
        // An array element's own name, where the file gives one ("SubIndex 001" is the default).
        if (!name.empty() && target->name.rfind("SubIndex ", 0) == 0)
          target->name = unique_name_undone(name, target->subindex);
      }
      if (target != nullptr) read_values(xml_, XmlReading::child(s, "Info"), *target);
    }
  }

  const XmlReading& xml_;
  std::map<std::string, TypeDef> types_;
};

}  // namespace

std::optional<BasicType> basic_type(std::string_view name, std::uint32_t bit_size) {
  struct Fixed {
    const char* name;
    DataType type;
    std::uint16_t bits;
  };
  // LINT/ULINT/LREAL: 8 bytes kept as they are (LREAL has no OD type of its own here).
  static constexpr Fixed kFixed[] = {
      {"BOOL", DataType::Boolean, 1},      {"BIT", DataType::Boolean, 1},        {"SINT", DataType::Integer8, 8},
      {"INT", DataType::Integer16, 16},    {"DINT", DataType::Integer32, 32},    {"LINT", DataType::Integer64, 64},
      {"USINT", DataType::Unsigned8, 8},   {"BYTE", DataType::Unsigned8, 8},     {"UINT", DataType::Unsigned16, 16},
      {"WORD", DataType::Unsigned16, 16},  {"UDINT", DataType::Unsigned32, 32},  {"DWORD", DataType::Unsigned32, 32},
      {"ULINT", DataType::Unsigned64, 64}, {"LWORD", DataType::Unsigned64, 64},  {"REAL", DataType::Real32, 32},
      {"LREAL", DataType::Unsigned64, 64}, {"INT24", DataType::Integer32, 24},   {"UINT24", DataType::Unsigned32, 24},
      {"BITARR8", DataType::Unsigned8, 8}, {"BITARR16", DataType::Unsigned16, 16}, {"BITARR32", DataType::Unsigned32, 32},
  };
  for (const Fixed& f : kFixed)
    if (name == f.name) return BasicType{f.type, f.bits};
  // BIT1..BIT8: an n-bit field of a byte.
  if (name.size() == 4 && name.substr(0, 3) == "BIT" && name[3] >= '1' && name[3] <= '8')
    return BasicType{DataType::Unsigned8, static_cast<std::uint16_t>(name[3] - '0')};
  for (const char* s : {"STRING", "VISIBLE_STRING"})
    if (const auto n = bracketed(name, s)) return BasicType{DataType::VisibleString, clamp_bits(8 * *n)};
  for (const char* s : {"OCTET_STRING", "UNICODE_STRING"})
    if (const auto n = bracketed(name, s)) return BasicType{DataType::OctetString, clamp_bits(8 * *n)};
  if (name == "STRING" || name == "VISIBLE_STRING") return BasicType{DataType::VisibleString, clamp_bits(bit_size)};
  if (name == "OCTET_STRING" || name == "UNICODE_STRING" || name == "GUID")
    return BasicType{DataType::OctetString, clamp_bits(name == "GUID" ? 128 : bit_size)};
  if (name.substr(0, 7) == "ARRAY [" && name.size() > 15 && name.substr(name.size() - 8) == " OF BYTE")
    return BasicType{DataType::OctetString, clamp_bits(bit_size)};
  return std::nullopt;
}

std::uint8_t coe_code(std::string_view name) {
  struct Code {
    const char* name;
    std::uint8_t code;
  };
  static constexpr Code kCodes[] = {
      {"BOOL", 0x01},  {"BIT", 0x01},   {"SINT", 0x02},  {"INT", 0x03},    {"DINT", 0x04},   {"USINT", 0x05},
      {"UINT", 0x06},  {"UDINT", 0x07}, {"REAL", 0x08},  {"INT24", 0x10},  {"LREAL", 0x11},  {"LINT", 0x15},
      {"UINT24", 0x16}, {"ULINT", 0x1B}, {"BYTE", 0x1E}, {"WORD", 0x1F},   {"DWORD", 0x20},  {"BITARR8", 0x2D},
      {"BITARR16", 0x2E}, {"BITARR32", 0x2F},
  };
  for (const Code& c : kCodes)
    if (name == c.name) return c.code;
  if (name.size() == 4 && name.substr(0, 3) == "BIT" && name[3] >= '1' && name[3] <= '8')
    return static_cast<std::uint8_t>(0x30 + (name[3] - '1'));
  if (name.substr(0, 6) == "STRING") return 0x09;
  if (name.substr(0, 12) == "OCTET_STRING") return 0x0A;
  return 0;
}

std::vector<od::ObjectDesc> read_dictionary(const XmlReading& xml, const tinyxml2::XMLElement* dictionary) {
  return DictionaryReader(xml).read(dictionary);
}

}  // namespace vdrive::esi
