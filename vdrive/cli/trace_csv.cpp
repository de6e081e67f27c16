#include "vdrive/cli/trace_csv.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <string_view>

namespace vdrive::cli {
namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t from = 0;
  while (true) {
    const std::size_t comma = line.find(',', from);
    std::string_view cell = line.substr(from, comma == std::string_view::npos ? std::string_view::npos : comma - from);
    while (!cell.empty() && (cell.front() == ' ' || cell.front() == '"')) cell.remove_prefix(1);
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '"' || cell.back() == '\r')) cell.remove_suffix(1);
    cells.push_back(cell);
    if (comma == std::string_view::npos) return cells;
    from = comma + 1;
  }
}

std::optional<std::size_t> column(const std::vector<std::string_view>& header, std::string_view name) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) return std::nullopt;
  return static_cast<std::size_t>(it - header.begin());
}

}  // namespace

TraceCsv read_trace_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw TraceCsvError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  std::string line;
  if (!std::getline(in, line) || line.find_first_not_of(" \r") == std::string::npos)
    throw TraceCsvError(fmt::format("{}: empty file, expected a header line naming the columns", path));
  const std::string header_line = line;
  const std::vector<std::string_view> header = split(header_line);

  std::optional<std::size_t> time = column(header, "time_ns");
  double time_scale = 1e-9;
  if (!time) {
    time = column(header, "time_s");
    time_scale = 1.0;
  }
  const char* names[] = {"slave", "position", "velocity", "torque", "following_error"};
  std::size_t cols[5] = {};
  std::vector<std::string> missing;
  if (!time) missing.push_back("time_ns (or time_s)");
  for (int i = 0; i < 5; ++i) {
    const std::optional<std::size_t> c = column(header, names[i]);
    if (c) cols[i] = *c;
    else missing.push_back(names[i]);
  }
  if (!missing.empty())
    throw TraceCsvError(fmt::format("{}:1: header lacks column(s) {} (it has: {})", path, fmt::join(missing, ", "),
                                    header_line.substr(0, 200)));

  const std::optional<std::size_t> al_state = column(header, "al_state"), error_code = column(header, "error_code"),
                                   station = column(header, "station");
  std::map<int, SlaveSeries> by_slave;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \r") == std::string::npos) continue;
    const std::vector<std::string_view> cells = split(line);
    if (cells.size() != header.size())
      throw TraceCsvError(fmt::format("{}:{}: {} values, the header names {}", path, line_no, cells.size(), header.size()));
    auto number = [&](std::size_t c) {
      const std::string text(cells[c]);
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
        throw TraceCsvError(fmt::format("{}:{}: {} '{}' is not a number", path, line_no, header[c], text));
      return v;
    };
    const double slave = number(cols[0]);
    if (slave != static_cast<double>(static_cast<int>(slave)))
      throw TraceCsvError(fmt::format("{}:{}: slave '{}' is not a whole number", path, line_no, cells[cols[0]]));
    SlaveSeries& s = by_slave[static_cast<int>(slave)];
    s.slave = static_cast<int>(slave);
    s.time_s.push_back(number(*time) * time_scale);
    s.position.push_back(number(cols[1]));
    s.velocity.push_back(number(cols[2]));
    s.torque.push_back(number(cols[3]));
    s.following_error.push_back(number(cols[4]));
    if (al_state) s.al_state.push_back(number(*al_state));
    if (error_code) s.error_code.push_back(number(*error_code));
    if (station) {
      const double a = number(*station);
      if (a < 0 || a > 0xFFFF || a != static_cast<double>(static_cast<int>(a)))
        throw TraceCsvError(fmt::format("{}:{}: station '{}' is no station address (0 to 0xFFFF)", path, line_no, cells[*station]));
      if (a != 0) s.station = static_cast<std::uint16_t>(a);
    }
  }
  if (by_slave.empty()) throw TraceCsvError(fmt::format("{}: no rows after the header", path));
  TraceCsv trace;
  for (auto& [slave, series] : by_slave) trace.slaves.push_back(std::move(series));
  return trace;
}

}  // namespace vdrive::cli
