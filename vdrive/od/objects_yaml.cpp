#include "vdrive/od/objects_yaml.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <limits>

#include <yaml-cpp/yaml.h>

#include "ethercat/little_endian.hpp"
#include "vdrive/profile/yaml_map_reader.hpp"

namespace vdrive::od {

namespace {

using profile::throw_at;

// The keys a mapping may hold; anything else is a format error (the file is generated, so an
// unknown key means the format moved on without this reader).
constexpr std::string_view kTopKeys[] = {"product", "manual", "table_lines", "object_count",
                                         "entry_count", "notes", "objects"};
constexpr std::string_view kObjectKeys[] = {"index", "name", "name_en", "object_code",
                                            "attributes", "line", "entries"};
constexpr std::string_view kEntryKeys[] = {"subindex", "name", "name_en", "data_type", "access",
                                           "writable_in", "pdo", "default", "min", "max", "units",
                                           "attributes", "synthesized", "overridden", "line"};

// One YAML mapping, its keys checked once; fields looked up by name.
class Fields {
public:
  template <std::size_t N>
  Fields(const YAML::Node& node, const std::string& file, std::string path,
         const std::string_view (&allowed)[N])
      : node_(node), file_(file), path_(std::move(path)) {
    if (!node.IsMap()) throw_at(file_, node.Mark(), path_ + ": expected a mapping");
    for (const auto& kv : node) {
      const std::string& key = kv.first.Scalar();
      const auto* known = std::find(std::begin(allowed), std::end(allowed), key);
      if (known == std::end(allowed)) throw_at(file_, kv.first.Mark(), field(key) + ": unknown field");
      const auto slot = static_cast<std::size_t>(known - std::begin(allowed));
      if (present_[slot]) throw_at(file_, kv.first.Mark(), field(key) + ": duplicate field");
      present_[slot] = true;
      values_[slot] = kv.second;
      keys_[slot] = allowed[slot];
    }
  }

  // The value of `key`, or an undefined node when absent.
  YAML::Node get(std::string_view key) const {
    for (std::size_t i = 0; i < kMax; ++i)
      if (present_[i] && keys_[i] == key) return values_[i];
    return YAML::Node(YAML::NodeType::Undefined);
  }
  YAML::Node required(std::string_view key) const {
    YAML::Node v = get(key);
    if (!v.IsDefined()) throw_at(file_, node_.Mark(), field(key) + ": missing");
    return v;
  }
  bool present_and_not_null(std::string_view key) const {
    const YAML::Node v = get(key);
    return v.IsDefined() && !v.IsNull();
  }

  [[noreturn]] void fail(std::string_view key, std::string_view what) const {
    const YAML::Node at = key.empty() ? YAML::Node() : get(key);
    throw_at(file_, at.IsDefined() && !key.empty() ? at.Mark() : node_.Mark(),
             (key.empty() ? path_ : field(key)) + ": " + std::string(what));
  }

  std::string field(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }

  std::int64_t integer(std::string_view key, std::int64_t lo, std::int64_t hi) const {
    const YAML::Node v = required(key);
    std::int64_t value = 0;
    if (!v.IsScalar() || !parse_integer(v.Scalar(), value)) fail(key, "expected an integer");
    if (value < lo || value > hi)
      fail(key, v.Scalar() + " is out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    return value;
  }
  std::optional<std::int64_t> optional_integer(std::string_view key) const {
    if (!present_and_not_null(key)) return std::nullopt;
    const YAML::Node v = get(key);
    std::int64_t value = 0;
    if (!v.IsScalar() || !parse_integer(v.Scalar(), value)) fail(key, "expected an integer or null");
    return value;
  }
  std::string string(std::string_view key) const {
    const YAML::Node v = required(key);
    if (!v.IsScalar()) fail(key, "expected a string");
    return v.Scalar();
  }
  std::optional<std::string> optional_string(std::string_view key) const {
    if (!present_and_not_null(key)) return std::nullopt;
    const YAML::Node v = get(key);
    if (!v.IsScalar()) fail(key, "expected a string or null");
    return v.Scalar();
  }

  // Decimal, or hexadecimal with 0x; an optional leading '-'.
  static bool parse_integer(std::string_view s, std::int64_t& out) {
    bool negative = false;
    if (!s.empty() && s[0] == '-') {
      negative = true;
      s.remove_prefix(1);
    }
    int base = 10;
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
      base = 16;
      s.remove_prefix(2);
    }
    std::uint64_t magnitude = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), magnitude, base);
    if (s.empty() || ec != std::errc{} || end != s.data() + s.size()) return false;
    constexpr auto kMaxMagnitude = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    if (magnitude > kMaxMagnitude + (negative ? 1 : 0)) return false;
    out = negative ? static_cast<std::int64_t>(0 - magnitude) : static_cast<std::int64_t>(magnitude);
    return true;
  }

private:
  static constexpr std::size_t kMax = std::size(kEntryKeys);
  YAML::Node node_;
  const std::string& file_;
  std::string path_;
  std::array<std::string_view, kMax> keys_{};
  std::array<YAML::Node, kMax> values_{};
  std::array<bool, kMax> present_{};
};

std::string hex4(std::uint32_t v) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string s = "0x0000";
  for (int i = 0; i < 4; ++i) s[static_cast<std::size_t>(5 - i)] = kDigits[(v >> (4 * i)) & 0xF];
  return s;
}

// The range a value of `type` can hold (BOOL: 0..1).
std::pair<std::int64_t, std::int64_t> type_range(DataType type) {
  switch (type) {
    case DataType::Boolean: return {0, 1};
    case DataType::Integer8: return {INT8_MIN, INT8_MAX};
    case DataType::Integer16: return {INT16_MIN, INT16_MAX};
    case DataType::Integer32: return {INT32_MIN, INT32_MAX};
    case DataType::Unsigned8: return {0, UINT8_MAX};
    case DataType::Unsigned16: return {0, UINT16_MAX};
    case DataType::Unsigned32: return {0, UINT32_MAX};
    default: return {std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()};
  }
}

std::vector<std::uint8_t> little_endian(std::int64_t value, std::size_t bytes) {
  std::vector<std::uint8_t> out(bytes);
  ecat::put_le(out, static_cast<std::uint64_t>(value));
  return out;
}

// ETG.1000.6 access bits of one entry.
std::uint16_t access_bits(const Fields& f) {
  const std::optional<std::string> access = f.optional_string("access");
  // null: the manual prints '-' (A6B manufacturer's-use and reserved entries): readable, not writable.
  std::uint16_t bits = access::kReadAll;
  bool writable = false;
  if (access) {
    if (*access == "rw") writable = true;
    else if (*access != "ro") f.fail("access", "expected ro, rw or null, got '" + *access + "'");
  }
  // A6B Attribute X: "read-only or otherwise unchangeable objects, or unsupported objects"
  // (manual L34150). Four rw entries carry it (606Ah, 607Bh:01/02, 6082h): not writable.
  const YAML::Node attributes = f.get("attributes");
  if (writable && attributes.IsMap()) {
    const YAML::Node effect = attributes["takes_effect"];
    if (effect.IsDefined() && effect.IsScalar() && effect.Scalar() == "X") writable = false;
  }
  if (writable) {
    const YAML::Node states = f.get("writable_in");
    if (!states.IsDefined() || states.IsNull()) {
      bits |= access::kWriteAll;
    } else {
      if (!states.IsSequence() || states.size() == 0) f.fail("writable_in", "expected a list of PREOP, SAFEOP, OP");
      for (const auto& s : states) {
        const std::string name = s.IsScalar() ? s.Scalar() : std::string();
        if (name == "PREOP") bits |= access::kWritePreOp;
        else if (name == "SAFEOP") bits |= access::kWriteSafeOp;
        else if (name == "OP") bits |= access::kWriteOp;
        else f.fail("writable_in", "expected PREOP, SAFEOP or OP, got '" + name + "'");
      }
    }
  } else if (f.present_and_not_null("writable_in") && access == "ro") {
    f.fail("writable_in", "given for a read-only entry");
  }
  const std::optional<std::string> pdo = f.optional_string("pdo");
  if (pdo) {
    if (*pdo == "rx") bits |= access::kRxPdoMappable;
    else if (*pdo == "tx") bits |= access::kTxPdoMappable;
    else if (*pdo != "no") f.fail("pdo", "expected \"no\", rx, tx or null, got '" + *pdo + "'");
  }
  return bits;
}

// attributes.fields of a hexadecimal digit-field parameter (DS5C1 `n.` parameters): each field's
// `digits` ("2" or "0-1") and `min`/`max` (the field's own value). Fields without min/max are free.
std::vector<DigitField> parse_digit_fields(const Fields& f, const EntryDesc& e) {
  std::vector<DigitField> out;
  const YAML::Node attributes = f.get("attributes");
  if (!attributes.IsDefined() || !attributes.IsMap()) return out;
  const YAML::Node fields = attributes["fields"];
  if (!fields.IsDefined()) return out;
  if (!fields.IsSequence()) f.fail("attributes", "fields: expected a list");
  const unsigned digits_in_value = e.bit_length / 4u;
  for (const YAML::Node& field : fields) {
    if (!field.IsMap()) f.fail("attributes", "fields: expected mappings");
    const YAML::Node lo_node = field["min"], hi_node = field["max"], digits = field["digits"];
    if (!lo_node.IsDefined() || !hi_node.IsDefined() || lo_node.IsNull() || hi_node.IsNull()) continue;
    if (!digits.IsDefined() || !digits.IsScalar()) f.fail("attributes", "fields: a field without digits");
    const std::string text = digits.Scalar();
    const std::size_t dash = text.find('-');
    std::int64_t first = 0, last = 0, lo = 0, hi = 0;
    if (!Fields::parse_integer(text.substr(0, dash), first) ||
        !Fields::parse_integer(dash == std::string::npos ? text : text.substr(dash + 1), last) || first < 0 ||
        last < first || static_cast<std::uint64_t>(last) >= digits_in_value)
      f.fail("attributes", "fields: digits '" + text + "' do not fit the value");
    if (!Fields::parse_integer(lo_node.Scalar(), lo) || !Fields::parse_integer(hi_node.Scalar(), hi))
      f.fail("attributes", "fields: min/max of digits " + text + " are not integers");
    const auto bits = static_cast<std::uint8_t>(4 * (last - first + 1));
    if (lo < 0 || hi < lo || hi >= (std::int64_t{1} << bits))
      f.fail("attributes", "fields: range of digits " + text + " does not fit them");
    out.push_back(DigitField{static_cast<std::uint8_t>(4 * first), bits, static_cast<std::uint16_t>(lo),
                             static_cast<std::uint16_t>(hi)});
  }
  return out;
}

EntryDesc parse_entry(const YAML::Node& node, const std::string& file, const std::string& path,
                      std::uint16_t index) {
  const Fields f(node, file, path, kEntryKeys);
  EntryDesc e;
  e.index = index;
  e.subindex = static_cast<std::uint8_t>(f.integer("subindex", 0, 0xFF));
  e.name = f.optional_string("name_en").value_or(f.string("name"));
  e.manual_line = f.get("line").IsDefined() ? static_cast<int>(f.integer("line", 0, std::numeric_limits<int>::max())) : 0;
  const std::optional<std::string> type_text = f.optional_string("data_type");
  if (!type_text) f.fail("data_type", "not given; the dictionary needs a type for every entry");
  const std::optional<DataType> type = parse_data_type(*type_text);
  if (!type || *type == DataType::Real32 || *type == DataType::Integer64 || *type == DataType::Unsigned64)
    f.fail("data_type", "expected U8, U16, U32, I8, I16, I32, BOOL, VS or OS, got '" + *type_text + "'");
  e.type = *type;
  e.access = access_bits(f);
  e.units = f.optional_string("units").value_or("");
  if (f.present_and_not_null("synthesized")) {
    const YAML::Node s = f.get("synthesized");
    if (!s.IsScalar() || (s.Scalar() != "true" && s.Scalar() != "false")) f.fail("synthesized", "expected true or false");
    e.synthesized = s.Scalar() == "true";
  }

  // Absent = null, as for every field that may be null.
  const YAML::Node def = f.present_and_not_null("default") ? f.get("default") : YAML::Node(YAML::NodeType::Null);
  if (is_string(e.type)) {
    if (f.present_and_not_null("min") || f.present_and_not_null("max")) f.fail("min", "a string has no range");
    if (!def.IsNull() && !def.IsScalar()) f.fail("default", "expected a string or null");
    const std::string text = def.IsNull() ? std::string() : def.Scalar();
    if (text.size() > 0xFFFF / 8) f.fail("default", "string longer than 8191 bytes");
    const std::size_t bytes = def.IsNull() ? kDefaultStringBytes : std::max<std::size_t>(text.size(), 1);
    e.bit_length = static_cast<std::uint16_t>(8 * bytes);
    e.default_value.assign(bytes, 0);
    std::copy(text.begin(), text.end(), e.default_value.begin());
    e.value_bytes = static_cast<std::uint32_t>(bytes);
    return e;
  }

  e.bit_length = fixed_bit_size(e.type);
  e.value_bytes = std::max<std::uint32_t>(1, (e.bit_length + 7u) / 8u);
  const auto [type_lo, type_hi] = type_range(e.type);
  e.min = f.optional_integer("min");
  e.max = f.optional_integer("max");
  if (e.min && (*e.min < type_lo || *e.min > type_hi)) f.fail("min", "does not fit " + std::string(short_name(e.type)));
  if (e.max && (*e.max < type_lo || *e.max > type_hi)) f.fail("max", "does not fit " + std::string(short_name(e.type)));
  if (e.min && e.max && *e.min > *e.max) f.fail("max", "is less than min");
  e.digit_fields = parse_digit_fields(f, e);
  const std::int64_t lo = e.min.value_or(type_lo), hi = e.max.value_or(type_hi);
  std::int64_t value = 0;
  if (def.IsNull()) {
    // No default in the manual: 0, or the nearest limit when 0 is outside the range.
    value = std::clamp<std::int64_t>(0, lo, hi);
  } else {
    if (!def.IsScalar() || !Fields::parse_integer(def.Scalar(), value)) f.fail("default", "expected an integer or null");
    if (value < lo || value > hi)
      f.fail("default", def.Scalar() + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
  }
  e.default_value = little_endian(value, e.value_bytes);
  return e;
}

ObjectCode parse_object_code(const Fields& f) {
  const std::string code = f.string("object_code");
  if (code == "VAR") return ObjectCode::Var;
  if (code == "ARRAY") return ObjectCode::Array;
  if (code == "RECORD") return ObjectCode::Record;
  f.fail("object_code", "expected VAR, ARRAY or RECORD, got '" + code + "'");
}

ObjectDesc parse_object(const YAML::Node& node, const std::string& file, const std::string& path) {
  const Fields f(node, file, path, kObjectKeys);
  ObjectDesc o;
  o.index = static_cast<std::uint16_t>(f.integer("index", 0, 0xFFFF));
  o.name = f.optional_string("name_en").value_or(f.string("name"));
  o.code = parse_object_code(f);
  if (f.get("line").IsDefined()) f.integer("line", 0, std::numeric_limits<int>::max());
  const YAML::Node entries = f.required("entries");
  if (!entries.IsSequence() || entries.size() == 0) f.fail("entries", "expected a non-empty list");
  o.entries.reserve(entries.size());
  const std::string prefix = path + " (" + hex4(o.index) + ").entries[";
  for (std::size_t i = 0; i < entries.size(); ++i) {
    EntryDesc e = parse_entry(entries[i], file, prefix + std::to_string(i) + "]", o.index);
    if (!o.entries.empty() && e.subindex <= o.entries.back().subindex)
      throw_at(file, entries[i].Mark(), prefix + std::to_string(i) + "].subindex: not above the previous entry's");
    o.entries.push_back(std::move(e));
  }
  if (o.code == ObjectCode::Var && (o.entries.size() != 1 || o.entries[0].subindex != 0))
    f.fail("entries", "a VAR has exactly one entry, subindex 0x00");
  return o;
}

}  // namespace

ObjectsYaml parse_objects_yaml(std::string_view text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw_at(file, e.mark, e.msg);
  }
  const Fields top(root, file, "", kTopKeys);
  ObjectsYaml out;
  out.product = top.string("product");
  const YAML::Node objects = top.required("objects");
  if (!objects.IsSequence()) top.fail("objects", "expected a list");
  out.objects.reserve(objects.size());
  std::size_t entries = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const std::string path = "objects[" + std::to_string(i) + "]";
    ObjectDesc o = parse_object(objects[i], file, path);
    if (!out.objects.empty() && o.index <= out.objects.back().index)
      throw_at(file, objects[i].Mark(), path + ".index: " + hex4(o.index) + " not above the previous object's");
    entries += o.entries.size();
    out.objects.push_back(std::move(o));
  }
  // The counts are optional (hand-written test files); when present they must be right.
  if (top.get("object_count").IsDefined() &&
      top.integer("object_count", 0, 0xFFFF) != static_cast<std::int64_t>(out.objects.size()))
    top.fail("object_count", "says " + top.get("object_count").Scalar() + ", the file has " +
                                 std::to_string(out.objects.size()));
  if (top.get("entry_count").IsDefined() &&
      top.integer("entry_count", 0, 0xFFFFFF) != static_cast<std::int64_t>(entries))
    top.fail("entry_count", "says " + top.get("entry_count").Scalar() + ", the file has " + std::to_string(entries));
  return out;
}

}  // namespace vdrive::od
