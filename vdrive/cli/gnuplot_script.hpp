#pragma once
// What `vdrive plot` hands to gnuplot: a data file (one block per slave: time in s, position,
// velocity, torque, following error) and a script drawing four stacked panels against time, one
// line per slave, into a PNG (pngcairo). The legend sits outside the panels so that everything
// inside a panel's frame is data, grid or tic marks.
#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/cli/trace_csv.hpp"

namespace vdrive::cli {

struct PlotSpec {
  std::string data_file;  // written by write_gnuplot_data
  std::string output;     // the PNG
  int width = 1200, height = 900;
  std::string title;      // empty: none
};

// Panels top to bottom, as drawn.
inline constexpr std::string_view kPanelNames[] = {"position", "velocity", "torque", "following error"};

// The colour of the i-th series drawn ("#RRGGBB"); a colour-blind-safe palette, repeating.
std::string_view series_colour(std::size_t i);

void write_gnuplot_data(std::ostream& out, const std::vector<const SlaveSeries*>& series);
// `slaves`: the slave number of each block of the data file, in order.
std::string gnuplot_script(const PlotSpec& spec, const std::vector<int>& slaves);

}  // namespace vdrive::cli
