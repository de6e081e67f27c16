#pragma once
// A line of slaves cut into consecutive parts, each served by its own process and chained to the
// next through the onward port (`vdrive run --processes N`, docs/scale-out.md). The first parts
// take one slave more when the slaves do not divide evenly, so no part is more than one slave
// larger than another.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace vdrive::network {

struct LinePart {
  std::size_t first = 0;  // 0-based index of its first slave in the whole line
  std::size_t count = 0;
};

// Throws std::invalid_argument ("the line has 2 slave(s); give 1 to 2") unless 1 <= parts <= slaves.
std::vector<LinePart> split_line(std::size_t slaves, std::size_t parts);

// The part holding slave `slave` (0-based), or parts.size() if none does.
std::size_t part_of(std::span<const LinePart> parts, std::size_t slave);

// How logs and errors name part `k` (0-based) holding `p`: "part 2 (slave 3)", "part 3 (slaves 4-5)".
std::string part_name(std::size_t k, LinePart p);

}  // namespace vdrive::network
