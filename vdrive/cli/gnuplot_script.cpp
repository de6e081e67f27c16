#include "vdrive/cli/gnuplot_script.hpp"

#include <fmt/format.h>

#include <array>

namespace vdrive::cli {
namespace {

// Okabe-Ito without black (the frames are black) and yellow (unreadable on white).
constexpr std::array<std::string_view, 6> kPalette = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"};

// A gnuplot single-quoted string: only the quote itself needs escaping (doubled).
std::string quoted(std::string_view text) {
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

void write_gnuplot_data(std::ostream& out, const std::vector<const SlaveSeries*>& series) {
  for (const SlaveSeries* s : series) {
    out << "# slave " << s->slave << "\n";
    for (std::size_t i = 0; i < s->time_s.size(); ++i)
      out << fmt::format("{:.9f} {} {} {} {}\n", s->time_s[i], s->position[i], s->velocity[i], s->torque[i],
                         s->following_error[i]);
    out << "\n\n";  // two blank lines end a block: gnuplot's `index`
  }
}

std::string gnuplot_script(const PlotSpec& spec, const std::vector<int>& slaves) {
  std::string s;
  s += fmt::format("set terminal pngcairo size {},{} noenhanced font 'sans,10'\n", spec.width, spec.height);
  s += fmt::format("set output {}\n", quoted(spec.output));
  s += spec.title.empty() ? "set multiplot layout 4,1\n" : fmt::format("set multiplot layout 4,1 title {}\n", quoted(spec.title));
  // Fixed margins (character cells) so the four panels line up whatever their tic labels.
  s += "set lmargin 14\nset rmargin 16\nset grid lc rgb '#dddddd'\nset key outside right top\n";
  s += "set format y '%g'\nset ytics nomirror\n";
  for (std::size_t p = 0; p < std::size(kPanelNames); ++p) {
    s += fmt::format("set ylabel {}\n", quoted(kPanelNames[p]));
    s += p + 1 == std::size(kPanelNames) ? "set xlabel 'time (s)'\n" : "unset xlabel\n";
    if (p == 1) s += "unset key\n";  // one legend, beside the top panel
    s += "plot ";
    for (std::size_t i = 0; i < slaves.size(); ++i) {
      s += fmt::format("{}{} index {} using 1:{} with lines lw 2 lc rgb '{}' title 'slave {}'", i == 0 ? "" : ", ",
                       i == 0 ? quoted(spec.data_file) : "''", i, p + 2, series_colour(i), slaves[i]);
    }
    s += "\n";
  }
  s += "unset multiplot\n";
  return s;
}

}  // namespace vdrive::cli
