#pragma once
// A product's motors as the plant sees them: plain MotorParams, already converted from the
// product's catalogue by the layer that knows products. A plant file's "motor: {product: <id>,
// model: <name>}" starts from one of these.
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "plant/plant_description.hpp"

namespace vdrive::plant {

struct MotorCatalogue {
  MotorParams default_motor;        // what "product:" alone gives
  std::vector<MotorParams> motors;  // by MotorParams::model, in catalogue order

  // The first motor named `model`, or nullptr.
  const MotorParams* find(std::string_view model) const {
    for (const MotorParams& m : motors)
      if (m.model == model) return &m;
    return nullptr;
  }
};

// A product's catalogue by product id; nullopt = unknown product.
using ProductLookup = std::function<std::optional<MotorCatalogue>(std::string_view id)>;

}  // namespace vdrive::plant
