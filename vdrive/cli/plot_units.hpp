#pragma once
// The units `vdrive plot` draws in. By default the drive's own: position and following error in
// position units (6064h, 60F4h; encoder counts unless the factor group was changed), velocity in
// position units per second (606Ch), torque in 0.1 % of rated torque (6077h). With revolutions,
// each slave's values are turned into motor revolutions, rev/s and % of rated torque, using the
// factor group its product holds at power-on as the drive latches it (motor revolutions per
// position unit = (6091h-1/6091h-2) / (6092h-1/6092h-2); no 6092h: one encoder revolution of
// 608Fh increments, 0 there: the default motor's encoder), so drives of different resolutions
// share one scale. A master that changed the factor group makes those numbers wrong; the plot
// prints what it assumed.
#include <string>
#include <vector>

namespace vdrive::cli {

struct PanelScale {
  // Multiply the trace's values by these (following error goes with position).
  double position = 1.0, velocity = 1.0, torque = 1.0, following_error = 1.0;
};

struct PlotUnits {
  std::string position, velocity, torque;  // axis unit text, e.g. "counts", "rev/s"
  std::vector<PanelScale> per_slave;       // by the order of the plotted slaves
  std::vector<std::string> notes;          // what the conversion assumed, per product
};

// The drive's own units for `slaves` plotted slaves.
PlotUnits drive_units(std::size_t slaves);

// Revolutions for plotted slaves whose products are `products` (built-in ids or --profile-dir
// ids, one per plotted slave). Throws CliError (bad arguments) for an unknown product or one whose
// factor group is missing or zero.
PlotUnits revolution_units(const std::vector<std::string>& products, const std::string& profile_dir);

}  // namespace vdrive::cli
