#include "vdrive/cli/plot_markers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>

#include "vdrive/runtime/line_status.hpp"

namespace vdrive::cli {
namespace {

// One CSV line into cells; a cell in double quotes may hold commas and "" for a quote.
std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cells.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else cells.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.emplace_back();
    } else if (c != '\r') {
      cells.back() += c;
    }
  }
  return cells;
}

PlotMarker::Kind kind_of(const std::string& kind) {
  if (kind.find("alarm") != std::string::npos || kind == "emergency") return PlotMarker::Kind::alarm;
  if (kind.rfind("al_", 0) == 0) return PlotMarker::Kind::al_state;
  if (kind.find("fault") != std::string::npos) return PlotMarker::Kind::fault;
  return PlotMarker::Kind::other;
}

}  // namespace

std::vector<PlotMarker> trace_markers(const std::vector<const SlaveSeries*>& series) {
  std::vector<PlotMarker> out;
  for (const SlaveSeries* s : series) {
    for (std::size_t i = 1; i < s->al_state.size(); ++i) {
      const int before = static_cast<int>(s->al_state[i - 1]), now = static_cast<int>(s->al_state[i]);
      if ((before & 0x1F) != (now & 0x1F))
        out.push_back({s->time_s[i], s->slave, PlotMarker::Kind::al_state,
                       fmt::format("S{} {}{}", s->slave, runtime::al_state_name(static_cast<std::uint16_t>(now)), (now & 0x10) != 0 ? "+E" : "")});
    }
    for (std::size_t i = 1; i < s->error_code.size(); ++i) {
      const auto before = static_cast<unsigned>(s->error_code[i - 1]), now = static_cast<unsigned>(s->error_code[i]);
      if (before != now)
        out.push_back({s->time_s[i], s->slave, PlotMarker::Kind::alarm,
                       now != 0 ? fmt::format("S{} alarm {:04X}h", s->slave, now) : fmt::format("S{} alarm cleared", s->slave)});
    }
  }
  std::sort(out.begin(), out.end(), [](const PlotMarker& a, const PlotMarker& b) { return a.time_s < b.time_s; });
  return out;
}

std::vector<PlotMarker> merge_simultaneous(std::vector<PlotMarker> markers) {
  std::stable_sort(markers.begin(), markers.end(), [](const PlotMarker& a, const PlotMarker& b) { return a.time_s < b.time_s; });
  std::vector<PlotMarker> out;
  for (PlotMarker& m : markers) {
    if (!out.empty() && out.back().kind == m.kind && std::abs(out.back().time_s - m.time_s) < 1e-6 && out.back().text.size() < 120) {
      out.back().text += ", " + m.text;
      out.back().slave = 0;
    } else {
      out.push_back(std::move(m));
    }
  }
  return out;
}

std::vector<PlotMarker> read_event_markers(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw TraceCsvError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  std::string line;
  if (!std::getline(in, line)) throw TraceCsvError(fmt::format("{}: empty file, expected the event log's header", path));
  const std::vector<std::string> header = cells_of(line);
  const auto col = [&](const char* name) -> std::optional<std::size_t> {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? std::nullopt : std::optional<std::size_t>(static_cast<std::size_t>(it - header.begin()));
  };
  const auto time = col("time_ns"), slave = col("slave"), kind = col("kind"), text = col("text");
  if (!time || !slave || !kind || !text)
    throw TraceCsvError(fmt::format("{}:1: an event log needs the columns time_ns, slave, kind and text", path));
  std::vector<PlotMarker> out;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \r") == std::string::npos) continue;
    const std::vector<std::string> c = cells_of(line);
    if (c.size() < header.size()) throw TraceCsvError(fmt::format("{}:{}: {} values, the header names {}", path, line_no, c.size(), header.size()));
    char* end = nullptr;
    errno = 0;
    const double t = std::strtod(c[*time].c_str(), &end);
    if (c[*time].empty() || *end != '\0' || errno == ERANGE)
      throw TraceCsvError(fmt::format("{}:{}: time_ns '{}' is not a number", path, line_no, c[*time]));
    const int s = std::atoi(c[*slave].c_str());
    std::string label = c[*text].substr(0, 40);
    out.push_back({t * 1e-9, s, kind_of(c[*kind]), s != 0 ? fmt::format("S{} {}", s, label) : label});
  }
  return out;
}

}  // namespace vdrive::cli
