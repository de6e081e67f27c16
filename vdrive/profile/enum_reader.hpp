#pragma once
// Enum-valued profile keys: each value has one lower_snake name; any other string is refused with
// the list of accepted names.
#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "vdrive/profile/yaml_map_reader.hpp"

namespace vdrive::profile {

template <typename E, std::size_t N>
E read_enum(YamlMapReader& m, std::string_view key, const std::array<std::pair<std::string_view, E>, N>& names) {
  const std::string s = m.string(key);
  for (const auto& [name, value] : names)
    if (s == name) return value;
  std::string list;
  for (const auto& [name, value] : names) list += (list.empty() ? "" : ", ") + std::string(name);
  m.fail(key, "is '" + s + "', expected one of " + list);
}

}  // namespace vdrive::profile
