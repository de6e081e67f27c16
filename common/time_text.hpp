#pragma once
// Times as users write them (scenario and network files, control requests): a number with a unit,
// "1.5s", "250ms", "125us", "40ns" (also "min"); a bare number is refused, so no file means
// milliseconds where another means seconds.
#include <optional>
#include <string_view>

#include "common/clock.hpp"

namespace vdrive {

// Nanoseconds, or nullopt for text that is not a non-negative time with a unit.
std::optional<Nanos> parse_time(std::string_view text);

}  // namespace vdrive
