#include "vdrive/network/line_parts.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace vdrive::network {

std::vector<LinePart> split_line(std::size_t slaves, std::size_t parts) {
  if (parts == 0 || parts > slaves)
    throw std::invalid_argument("the line has " + std::to_string(slaves) + " slave(s); give 1 to " + std::to_string(slaves));
  std::vector<LinePart> out;
  std::size_t first = 0;
  for (std::size_t k = 0; k < parts; ++k) {
    const std::size_t count = slaves / parts + (k < slaves % parts ? 1 : 0);
    out.push_back(LinePart{first, count});
    first += count;
  }
  return out;
}

std::size_t part_of(std::span<const LinePart> parts, std::size_t slave) {
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (slave >= parts[k].first && slave < parts[k].first + parts[k].count) return k;
  return parts.size();
}

std::string part_name(std::size_t k, LinePart p) {
  return p.count == 1 ? fmt::format("part {} (slave {})", k + 1, p.first + 1)
                      : fmt::format("part {} (slaves {}-{})", k + 1, p.first + 1, p.first + p.count);
}

}  // namespace vdrive::network
