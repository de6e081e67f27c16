#pragma once
// What `vdrive plot` hands to gnuplot: a data file (one block per slave: time in s, position,
// velocity, torque, following error, each scaled into the plot's units) and a script drawing four
// stacked panels against time, one line per slave, into a PNG (pngcairo). The legend sits outside
// the panels so that everything inside a panel's frame is data, grid, tic marks or a marker:
// markers (AL changes grey, alarms red, faults orange, other events blue) are dashed vertical
// lines through every panel, labelled inside the top one.
#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/cli/plot_markers.hpp"
#include "vdrive/cli/plot_units.hpp"
#include "vdrive/cli/trace_csv.hpp"

namespace vdrive::cli {

struct PlotSpec {
  std::string data_file;  // written by write_gnuplot_data
  std::string output;     // the PNG
  int width = 1200, height = 900;
  std::string title;      // empty: none
  std::array<std::string, 4> ylabels;    // per panel, with its unit
  std::vector<std::string> series_names;  // legend, per block of the data file
  std::vector<PlotMarker> markers;
};

// Labels in the top panel at most; markers beyond are drawn without one.
inline constexpr std::size_t kMaxMarkerLabels = 40;
inline constexpr std::size_t kMaxMarkers = 400;
inline constexpr std::size_t kMaxLabelChars = 34;

// Panels top to bottom, as drawn.
inline constexpr std::string_view kPanelNames[] = {"position", "velocity", "torque", "following error"};

// The colour of the i-th series drawn ("#RRGGBB"); a colour-blind-safe palette, repeating.
std::string_view series_colour(std::size_t i);

// `scales`: one per series, the factors into the plot's units.
void write_gnuplot_data(std::ostream& out, const std::vector<const SlaveSeries*>& series, const std::vector<PanelScale>& scales);
std::string gnuplot_script(const PlotSpec& spec);

}  // namespace vdrive::cli
