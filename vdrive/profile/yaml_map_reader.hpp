#pragma once
// Typed, strict reading of one YAML mapping of a profile file. Every field is read by name; a
// missing field, a value of the wrong type, a duplicate key or a key nobody asked for (checked by
// finish()) throws ProfileError "<file>:<line>: <field path>: <what was expected>".
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {

class YamlMapReader {
public:
  // `file` names the source in messages; `path` is the mapping's dotted path ("" for the root).
  // Errors about the mapping as a whole (a missing field) point at `line` (0-based), by default
  // where the mapping starts; a nested mapping passes the line of its key.
  YamlMapReader(const YAML::Node& node, std::string file, std::string path, int line = -1);

  bool has(std::string_view key) const;

  std::uint8_t u8(std::string_view key);
  std::uint16_t u16(std::string_view key);
  std::uint32_t u32(std::string_view key);
  std::int8_t i8(std::string_view key);
  std::int16_t i16(std::string_view key);
  double real(std::string_view key);                   // a finite decimal number, >= 0
  bool boolean(std::string_view key);
  // Sequences of integers, e.g. [125000, 250000] or [0x00, 0x03]; each element range-checked.
  std::vector<std::uint8_t> u8_list(std::string_view key);
  std::vector<std::uint16_t> u16_list(std::string_view key);
  std::vector<std::uint32_t> u32_list(std::string_view key);
  std::vector<std::int8_t> i8_list(std::string_view key);
  std::string string(std::string_view key, std::size_t max_bytes = 255);
  YAML::Node sequence(std::string_view key);          // a YAML sequence
  YamlMapReader map(std::string_view key);             // a nested mapping

  // An element of a sequence read from this mapping, e.g. element(seq, "sync_managers", 2).
  YamlMapReader element(const YAML::Node& seq, std::string_view key, std::size_t i) const;

  // Throws for the first key that was never read.
  void finish() const;

  // Throws ProfileError for `key` (or for the mapping itself when key is empty).
  [[noreturn]] void fail(std::string_view key, std::string_view what) const;

  const std::string& file() const { return file_; }

private:
  YAML::Node get(std::string_view key);                // marks the key used; throws if missing
  std::uint64_t unsigned_value(std::string_view key, std::uint64_t max, std::string_view expected);
  std::int64_t signed_value(std::string_view key, std::int64_t min, std::int64_t max, std::string_view expected);
  // Parses one scalar node as an integer in [min, max]; `field` names it in the error.
  std::int64_t integer_at(const YAML::Node& v, const std::string& field, int line, std::int64_t min,
                          std::int64_t max, std::string_view expected) const;
  template <typename T>
  std::vector<T> integer_list(std::string_view key, std::int64_t min, std::int64_t max, std::string_view expected);
  std::string field(std::string_view key) const;
  int line_of(std::string_view key) const;

  YAML::Node node_;
  std::string file_;
  std::string path_;
  int line_;
  std::set<std::string, std::less<>> used_;
};

// "<file>:<line>: <message>" for errors found in a node.
[[noreturn]] void throw_at(const std::string& file, const YAML::Mark& mark, std::string_view message);

}  // namespace vdrive::profile
