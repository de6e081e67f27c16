#include "common/time_text.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

namespace vdrive {

std::optional<Nanos> parse_time(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  std::size_t unit = 0;
  while (unit < text.size() && (std::isdigit(static_cast<unsigned char>(text[unit])) || text[unit] == '.')) ++unit;
  if (unit == 0) return std::nullopt;
  double value = 0.0;
  const std::string number(text.substr(0, unit));
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (ec != std::errc{} || end != number.data() + number.size()) return std::nullopt;
  std::string_view suffix = text.substr(unit);
  while (!suffix.empty() && suffix.front() == ' ') suffix.remove_prefix(1);
  double scale = 0.0;
  if (suffix == "ns") scale = 1.0;
  else if (suffix == "us") scale = 1e3;
  else if (suffix == "ms") scale = 1e6;
  else if (suffix == "s") scale = 1e9;
  else if (suffix == "min") scale = 60e9;
  else return std::nullopt;
  const double ns = value * scale;
  if (!std::isfinite(ns) || ns > 9.2e18) return std::nullopt;
  return static_cast<Nanos>(std::llround(ns));
}

}  // namespace vdrive
