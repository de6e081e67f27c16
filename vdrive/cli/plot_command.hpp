#pragma once
// `vdrive plot TRACE.csv [-o OUT.png] [--slave K] [--title T] [--size WxH] [--from-zero]`: position, velocity,
// torque and following error against time, four stacked panels, one line per slave, drawn by
// gnuplot (pngcairo) from a scenario trace or a telemetry CSV (columns by header name, see
// trace_csv.hpp). Exit 2 for a bad option or input file, 5 when gnuplot is not installed, 1 when
// it fails or the PNG cannot be written.
namespace CLI { class App; }

namespace vdrive::cli {
void add_plot_command(CLI::App& app);
}
