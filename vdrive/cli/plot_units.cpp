#include "vdrive/cli/plot_units.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <memory>
#include <numbers>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/exit_codes.hpp"
#include "plant/plant_description.hpp"
#include "vdrive/drive/product_plant.hpp"
#include "vdrive/drive/unit_scaling.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::cli {
namespace {

// A power-on value of a 32-bit entry: 0 for absent.
std::uint32_t default_of(const od::Dictionary& d, std::uint16_t index, std::uint8_t sub) {
  const od::EntryDesc* e = d.find(index, sub);
  if (e == nullptr) return 0;
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < e->default_value.size() && i < 4; ++i) v |= static_cast<std::uint32_t>(e->default_value[i]) << (8 * i);
  return v;
}

}  // namespace

PlotUnits drive_units(std::size_t slaves) {
  PlotUnits u{"counts", "counts/s", "0.1 % rated", std::vector<PanelScale>(slaves), {}};
  return u;
}

PlotUnits revolution_units(const std::vector<std::string>& products, const std::string& profile_dir) {
  PlotUnits u{"rev", "rev/s", "% rated", {}, {}};
  for (const std::string& id : products) {
    const profile::ProductProfile profile = [&] {
      try {
        return profile::load_profile(id, profile_dir);
      } catch (const profile::ProfileError& e) {
        throw CliError(kExitBadArguments, fmt::format("--drive {}: {}", id, e.what()));
      }
    }();
    const std::shared_ptr<const od::Dictionary> d = od::shared_dictionary(profile);
    // The power-on values, as the drive latches them (drive::factor_group).
    const plant::PlantDescription plant = drive::default_plant(profile);
    const drive::FactorObjects objects{default_of(*d, 0x608F, 1), default_of(*d, 0x608F, 2), default_of(*d, 0x6091, 1),
                                       default_of(*d, 0x6091, 2), d->find(0x6092, 1) != nullptr, default_of(*d, 0x6092, 1),
                                       default_of(*d, 0x6092, 2), 0};
    drive::UnitScaling units;
    units.apply(drive::factor_group(objects, plant.axes.empty() ? 1 : plant.axes.front().encoder.counts_per_rev));
    const double rev_per_user = units.motor_rad_per_user() / (2.0 * std::numbers::pi);  // motor revolutions per position unit
    u.per_slave.push_back(PanelScale{rev_per_user, rev_per_user, 0.1, rev_per_user});
    u.notes.push_back(fmt::format("{}: {:g} position units per motor revolution (608Fh, 6091h, 6092h at power-on)", id,
                                  1.0 / rev_per_user));
  }
  return u;
}

}  // namespace vdrive::cli
