#include "vdrive/cli/gnuplot_script.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace vdrive::cli {
namespace {

// Okabe-Ito without black (the frames are black) and yellow (unreadable on white).
constexpr std::array<std::string_view, 6> kPalette = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"};

// A gnuplot single-quoted string: only the quote itself needs escaping (doubled).
std::string gnuplot_quoted(std::string_view text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\n' || c == '\r') out += ' ';
    else if (c == '\'') out += "''";
    else out += c;
  }
  return out + "'";
}

}  // namespace

std::string_view series_colour(std::size_t i) { return kPalette[i % kPalette.size()]; }

void write_gnuplot_data(std::ostream& out, const std::vector<const SlaveSeries*>& series, const std::vector<PanelScale>& scales) {
  for (std::size_t k = 0; k < series.size(); ++k) {
    const SlaveSeries* s = series[k];
    const PanelScale f = k < scales.size() ? scales[k] : PanelScale{};
    out << "# slave " << s->slave << "\n";
    for (std::size_t i = 0; i < s->time_s.size(); ++i)
      out << fmt::format("{:.9f} {:.9g} {:.9g} {:.9g} {:.9g}\n", s->time_s[i], s->position[i] * f.position,
                         s->velocity[i] * f.velocity, s->torque[i] * f.torque, s->following_error[i] * f.following_error);
    out << "\n\n";  // two blank lines end a block: gnuplot's `index`
  }
}

namespace {

std::string_view marker_colour(PlotMarker::Kind kind) {
  switch (kind) {
    case PlotMarker::Kind::al_state: return "#888888";
    case PlotMarker::Kind::alarm: return "#C00000";
    case PlotMarker::Kind::fault: return "#E69F00";
    case PlotMarker::Kind::other: break;
  }
  return "#56B4E9";
}

}  // namespace

std::string gnuplot_script(const PlotSpec& spec) {
  std::string s;
  s += fmt::format("set terminal pngcairo size {},{} noenhanced font 'sans,10'\n", spec.width, spec.height);
  s += fmt::format("set output {}\n", gnuplot_quoted(spec.output));
  s += spec.title.empty() ? "set multiplot layout 4,1\n" : fmt::format("set multiplot layout 4,1 title {}\n", gnuplot_quoted(spec.title));
  // Fixed margins (character cells) so the four panels line up whatever their tic labels.
  s += "set lmargin 14\nset rmargin 26\nset grid lc rgb '#dddddd'\nset key outside right top\n";
  s += "set format y '%g'\nset ytics nomirror\n";
  const std::size_t markers = std::min(spec.markers.size(), kMaxMarkers);
  for (std::size_t m = 0; m < markers; ++m) {
    const PlotMarker& k = spec.markers[m];
    s += fmt::format("set arrow {} from {:.9f}, graph 0 to {:.9f}, graph 1 nohead dt 2 lw 1 lc rgb '{}' back\n", m + 1,
                     k.time_s, k.time_s, marker_colour(k.kind));
  }
  for (std::size_t p = 0; p < std::size(kPanelNames); ++p) {
    s += fmt::format("set ylabel {}\n", gnuplot_quoted(spec.ylabels[p].empty() ? std::string(kPanelNames[p]) : spec.ylabels[p]));
    s += p + 1 == std::size(kPanelNames) ? "set xlabel 'time (s)'\n" : "unset xlabel\n";
    if (p == 0) {
      for (std::size_t m = 0; m < std::min(markers, kMaxMarkerLabels); ++m) {
        // Rotated inside the top panel: a label longer than the panel is high would run into the next.
        const std::string& text = spec.markers[m].text;
        const std::string label = text.size() <= kMaxLabelChars ? text : text.substr(0, kMaxLabelChars - 3) + "...";
        s += fmt::format("set label {} {} at {:.9f}, graph 0.97 right rotate by 90 offset -0.3,0 font ',7' tc rgb '{}' front\n", m + 1,
                         gnuplot_quoted(label), spec.markers[m].time_s, marker_colour(spec.markers[m].kind));
      }
    }
    if (p == 1) s += "unset key\nunset label\n";  // one legend and the labels, beside and above the top panel
    s += "plot ";
    for (std::size_t i = 0; i < spec.series_names.size(); ++i) {
      s += fmt::format("{}{} index {} using 1:{} with lines lw 2 lc rgb '{}' title {}", i == 0 ? "" : ", ",
                       i == 0 ? gnuplot_quoted(spec.data_file) : "''", i, p + 2, series_colour(i), gnuplot_quoted(spec.series_names[i]));
    }
    s += "\n";
  }
  s += "unset multiplot\n";
  return s;
}

}  // namespace vdrive::cli
