#pragma once
// Plant descriptions in YAML (format: docs/plant.md, example: scenarios/two_link_arm.yaml).
// Strict: unknown keys, wrong types, out-of-range values and dangling names are errors whose
// message starts with "<file>:<line>:<column>: <field path>:", e.g.
//   "arm.yaml:31:16: axes[1].transmission.ratio: must be > 0".
// Bodies not moved by a file keep PlantDescription's defaults. A motor may start from a product's
// catalogue ("product: a6b", optional "model:"), then override single fields.
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "plant/plant_description.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::plant {

class PlantYamlError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Looks a product up by id (e.g. wraps vdrive::profile::load_profile); nullptr = unknown.
using ProductLookup = std::function<const profile::ProductProfile*(std::string_view id)>;

PlantDescription parse_plant_yaml(std::string_view text, const std::string& origin,
                                  const ProductLookup& products = {});
PlantDescription load_plant_file(const std::string& path, const ProductLookup& products = {});

}  // namespace vdrive::plant
