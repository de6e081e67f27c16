#include "vdrive/profile/yaml_map_reader.hpp"

#include <charconv>

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
