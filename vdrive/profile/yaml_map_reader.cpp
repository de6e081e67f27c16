#include "vdrive/profile/yaml_map_reader.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace vdrive::profile {

void throw_at(const std::string& file, const YAML::Mark& mark, std::string_view message) {
  std::string where = file;
  if (!mark.is_null()) where += ":" + std::to_string(mark.line + 1);
  throw ProfileError(where + ": " + std::string(message));
}

YamlMapReader::YamlMapReader(const YAML::Node& node, std::string file, std::string path, int line)
    : node_(node), file_(std::move(file)), path_(std::move(path)), line_(line < 0 ? node.Mark().line : line) {
  if (!node_.IsMap()) fail({}, "expected a mapping");
  std::set<std::string, std::less<>> seen;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) throw_at(file_, kv.first.Mark(), path_ + ": keys must be plain names");
    const std::string& key = kv.first.Scalar();
    if (!seen.insert(key).second) throw_at(file_, kv.first.Mark(), field(key) + ": duplicate key");
  }
}

std::string YamlMapReader::field(std::string_view key) const {
  if (key.empty()) return path_.empty() ? std::string("(top level)") : path_;
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

int YamlMapReader::line_of(std::string_view key) const {
  if (!key.empty()) {
    for (const auto& kv : node_)
      if (kv.first.Scalar() == key) return kv.first.Mark().line;
  }
  return line_;
}

void YamlMapReader::fail(std::string_view key, std::string_view what) const {
  YAML::Mark mark = node_.Mark();
  mark.line = line_of(key);
  throw_at(file_, mark, field(key) + ": " + std::string(what));
}

bool YamlMapReader::has(std::string_view key) const {
  for (const auto& kv : node_)
    if (kv.first.Scalar() == key) return true;
  return false;
}

YAML::Node YamlMapReader::get(std::string_view key) {
  for (const auto& kv : node_) {
    if (kv.first.Scalar() == key) {
      used_.emplace(key);
      return kv.second;
    }
  }
  fail(key, "missing");
}

std::uint64_t YamlMapReader::unsigned_value(std::string_view key, std::uint64_t max,
                                            std::string_view expected) {
  const YAML::Node v = get(key);
  const std::string what = "expected " + std::string(expected);
  if (!v.IsScalar()) fail(key, what);
  std::string_view s = v.Scalar();
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  }
  if (s.empty() || s[0] == '+' || s[0] == '-') fail(key, what);
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value, base);
  if (ec != std::errc{} || end != s.data() + s.size() || value > max) fail(key, what);
  return value;
}

std::uint8_t YamlMapReader::u8(std::string_view key) {
  return static_cast<std::uint8_t>(unsigned_value(key, 0xFF, "an unsigned 8-bit integer"));
}

std::uint16_t YamlMapReader::u16(std::string_view key) {
  return static_cast<std::uint16_t>(unsigned_value(key, 0xFFFF, "an unsigned 16-bit integer"));
}

std::uint32_t YamlMapReader::u32(std::string_view key) {
  return static_cast<std::uint32_t>(unsigned_value(key, 0xFFFFFFFF, "an unsigned 32-bit integer"));
}

std::int64_t YamlMapReader::integer_at(const YAML::Node& v, const std::string& field, int line, std::int64_t min,
                                       std::int64_t max, std::string_view expected) const {
  const std::string what = field + ": expected " + std::string(expected);
  YAML::Mark mark = v.Mark();
  if (mark.is_null()) {  // a node without position: point at the key's line
    mark = node_.Mark();
    mark.line = line;
  }
  if (!v.IsScalar()) throw_at(file_, mark, what);
  std::string_view s = v.Scalar();
  const bool negative = !s.empty() && s[0] == '-';
  if (negative) s.remove_prefix(1);
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  }
  std::uint64_t magnitude = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), magnitude, base);
  if (s.empty() || s[0] == '+' || s[0] == '-' || ec != std::errc{} || end != s.data() + s.size() ||
      magnitude > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    throw_at(file_, mark, what);
  const std::int64_t value = negative ? -static_cast<std::int64_t>(magnitude) : static_cast<std::int64_t>(magnitude);
  if (value < min || value > max) throw_at(file_, mark, what);
  return value;
}

std::int64_t YamlMapReader::signed_value(std::string_view key, std::int64_t min, std::int64_t max,
                                         std::string_view expected) {
  const YAML::Node v = get(key);
  return integer_at(v, field(key), line_of(key), min, max, expected);
}

std::int8_t YamlMapReader::i8(std::string_view key) {
  return static_cast<std::int8_t>(signed_value(key, -128, 127, "a signed 8-bit integer"));
}

std::int16_t YamlMapReader::i16(std::string_view key) {
  return static_cast<std::int16_t>(signed_value(key, -32768, 32767, "a signed 16-bit integer"));
}

double YamlMapReader::real(std::string_view key) {
  const YAML::Node v = get(key);
  if (!v.IsScalar()) fail(key, "expected a number >= 0");
  const std::string& s = v.Scalar();
  double value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(value) || value < 0)
    fail(key, "expected a number >= 0");
  return value;
}

template <typename T>
std::vector<T> YamlMapReader::integer_list(std::string_view key, std::int64_t min, std::int64_t max,
                                           std::string_view expected) {
  const YAML::Node seq = sequence(key);
  std::vector<T> out;
  out.reserve(seq.size());
  for (std::size_t i = 0; i < seq.size(); ++i)
    out.push_back(static_cast<T>(
        integer_at(seq[i], field(key) + "[" + std::to_string(i) + "]", line_of(key), min, max, expected)));
  return out;
}

std::vector<std::uint8_t> YamlMapReader::u8_list(std::string_view key) {
  return integer_list<std::uint8_t>(key, 0, 0xFF, "an unsigned 8-bit integer");
}

std::vector<std::uint16_t> YamlMapReader::u16_list(std::string_view key) {
  return integer_list<std::uint16_t>(key, 0, 0xFFFF, "an unsigned 16-bit integer");
}

std::vector<std::uint32_t> YamlMapReader::u32_list(std::string_view key) {
  return integer_list<std::uint32_t>(key, 0, 0xFFFFFFFF, "an unsigned 32-bit integer");
}

std::vector<std::int8_t> YamlMapReader::i8_list(std::string_view key) {
  return integer_list<std::int8_t>(key, -128, 127, "a signed 8-bit integer");
}

bool YamlMapReader::boolean(std::string_view key) {
  const YAML::Node v = get(key);
  if (v.IsScalar() && v.Scalar() == "true") return true;
  if (v.IsScalar() && v.Scalar() == "false") return false;
  fail(key, "expected true or false");
}

std::string YamlMapReader::string(std::string_view key, std::size_t max_bytes) {
  const YAML::Node v = get(key);
  if (!v.IsScalar()) fail(key, "expected a string");
  if (v.Scalar().size() > max_bytes)
    fail(key, "expected a string of at most " + std::to_string(max_bytes) + " bytes");
  return v.Scalar();
}

YAML::Node YamlMapReader::sequence(std::string_view key) {
  const YAML::Node v = get(key);
  if (!v.IsSequence()) fail(key, "expected a list");
  return v;
}

YamlMapReader YamlMapReader::map(std::string_view key) {
  const YAML::Node v = get(key);
  if (!v.IsMap()) fail(key, "expected a mapping");
  return YamlMapReader(v, file_, field(key), line_of(key));
}

YamlMapReader YamlMapReader::element(const YAML::Node& seq, std::string_view key, std::size_t i) const {
  return YamlMapReader(seq[i], file_, field(key) + "[" + std::to_string(i) + "]");
}

void YamlMapReader::finish() const {
  for (const auto& kv : node_) {
    if (!used_.contains(kv.first.Scalar()))
      throw_at(file_, kv.first.Mark(), field(kv.first.Scalar()) + ": unknown field");
  }
}

}  // namespace vdrive::profile
