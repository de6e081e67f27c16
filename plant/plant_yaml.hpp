#pragma once
// Plant descriptions in YAML (format: docs/plant.md, example: scenarios/two_link_arm.yaml).
// Strict: unknown keys, wrong types, out-of-range values and dangling names are errors whose
// message starts with "<file>:<line>:<column>: <field path>:", e.g.
//   "arm.yaml:31:16: axes[1].transmission.ratio: must be > 0".
// Bodies not moved by a file keep PlantDescription's defaults. A motor may start from a product's
// catalogue ("product: <id>", optional "model:", looked up through a ProductLookup), then override
// single fields.
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "plant/motor_catalogue.hpp"
#include "plant/plant_description.hpp"

namespace vdrive::plant {

class PlantYamlError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

PlantDescription parse_plant_yaml(std::string_view text, const std::string& origin,
                                  const ProductLookup& products = {});
PlantDescription load_plant_file(const std::string& path, const ProductLookup& products = {});

}  // namespace vdrive::plant
