#include "vdrive/od/dictionary.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "vdrive/od/default_pdo_objects.hpp"
#include "vdrive/od/identity_objects.hpp"
#include "vdrive/od/objects_yaml.hpp"
#include "vdrive/profile/embedded_profiles.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::od {

const EntryDesc* ObjectDesc::entry(std::uint8_t subindex) const {
  const auto it = std::lower_bound(entries.begin(), entries.end(), subindex,
                                   [](const EntryDesc& e, std::uint8_t s) { return e.subindex < s; });
  return it != entries.end() && it->subindex == subindex ? &*it : nullptr;
}

const ObjectDesc* Dictionary::find(std::uint16_t index) const {
  const auto it = std::lower_bound(objects_.begin(), objects_.end(), index,
                                   [](const ObjectDesc& o, std::uint16_t i) { return o.index < i; });
  return it != objects_.end() && it->index == index ? &*it : nullptr;
}

const EntryDesc* Dictionary::find(std::uint16_t index, std::uint8_t subindex) const {
  const ObjectDesc* o = find(index);
  return o ? o->entry(subindex) : nullptr;
}

std::size_t Dictionary::entry_count() const {
  std::size_t n = 0;
  for (const ObjectDesc& o : objects_) n += o.entries.size();
  return n;
}

namespace {

struct Source {
  std::string file;   // for messages
  std::string text;   // empty: the product has no objects.yaml
};

// `<profile_dir>/<id>/objects.yaml` when that file exists, else the embedded copy.
Source find_objects_yaml(const std::string& id, const std::string& profile_dir) {
  if (!profile_dir.empty()) {
    const std::filesystem::path path = std::filesystem::path(profile_dir) / id / "objects.yaml";
    if (std::filesystem::exists(path)) {
      std::ifstream in(path, std::ios::binary);
      if (!in) throw profile::ProfileError(path.string() + ": cannot read");
      std::ostringstream text;
      text << in.rdbuf();
      return {path.string(), text.str()};
    }
  }
  for (const profile::EmbeddedProfile& p : profile::embedded_profiles())
    if (p.id == id) return {"profiles/" + id + "/objects.yaml (embedded)", profile::embedded_objects_yaml(p)};
  return {};
}

}  // namespace

Dictionary Dictionary::load(const profile::ProductProfile& profile, const std::string& profile_dir) {
  const Source source = find_objects_yaml(profile.id, profile_dir);
  // A product without objects.yaml still answers its identity (a profile under test, a new product).
  if (source.text.empty()) return from_objects({}, profile, /*complete_pdo_objects=*/false);
  ObjectsYaml parsed = parse_objects_yaml(source.text, source.file);
  if (parsed.product != profile.id)
    throw profile::ProfileError(source.file + ": product: '" + parsed.product + "', expected '" +
                                profile.id + "'");
  return from_objects(std::move(parsed.objects), profile);
}

Dictionary Dictionary::from_objects(std::vector<ObjectDesc> objects, const profile::ProductProfile& profile,
                                    bool complete_pdo_objects) {
  Dictionary d;
  d.objects_ = std::move(objects);
  std::sort(d.objects_.begin(), d.objects_.end(),
            [](const ObjectDesc& a, const ObjectDesc& b) { return a.index < b.index; });
  apply_identity(d.objects_, profile.identity);
  if (complete_pdo_objects) apply_default_pdo_configuration(d.objects_, profile);

  // One flat value array: each entry's bytes at its offset, in index/subindex order.
  std::uint32_t offset = 0;
  for (ObjectDesc& o : d.objects_) {
    for (EntryDesc& e : o.entries) {
      e.value_offset = offset;
      offset += e.value_bytes;
    }
  }
  d.value_bytes_ = offset;
  return d;
}

}  // namespace vdrive::od
