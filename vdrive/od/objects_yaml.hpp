#pragma once
// Reads the text of a profiles/<id>/objects.yaml (format: docs/object-dictionaries.md) into
// object descriptions, as printed: no identity values, no storage layout yet (Dictionary::load
// adds those). Every error throws profile::ProfileError "<file>:<line>: <field>: <problem>".
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/od/dictionary.hpp"

namespace vdrive::od {

struct ObjectsYaml {
  std::string product;               // the file's `product:` (must be the profile's id)
  std::vector<ObjectDesc> objects;   // sorted by index, entries sorted by subindex
};

ObjectsYaml parse_objects_yaml(std::string_view text, const std::string& file);

// Bytes given to a string entry whose objects.yaml default is null: 16, the size of the longest
// fixed-size string any of the manuals documents (A6B 10F3h diagnosis messages, L9106-L9134;
// A6B 1008h is "16 characters + NUL", L6549-L6564, but comes from the profile).
constexpr std::uint16_t kDefaultStringBytes = 16;

}  // namespace vdrive::od
