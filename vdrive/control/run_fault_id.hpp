#pragma once
// Fault ids across the parts of `vdrive run --processes N` (docs/scale-out.md). Each part's
// FaultInjector numbers its own faults 1, 2, ...; the user sees one run and must not see two
// faults with one id. Part k's (1-based) fault i is shown as run-wide id (i - 1) * N + k: the ids
// interleave, part 1 has 1, N + 1, 2N + 1, ..., part 2 has 2, N + 2, ..., and one process (N = 1)
// keeps its own ids unchanged. The mapping is arithmetic, so part 1 keeps no table that could
// disagree with a part's own list. Id 0 (a one-shot fault, not kept) stays 0.
#include <cstddef>
#include <limits>

namespace vdrive::control {

struct PartFaultId {
  std::size_t part = 0;  // 0-based: 0 is part 1
  int id = 0;            // that part's own id
};

// Part `part`'s (0-based) fault `id` among `parts` parts; 0 stays 0; -1 if it does not fit an int.
inline int run_fault_id(std::size_t part, int id, std::size_t parts) {
  if (id <= 0) return 0;
  const long long run = static_cast<long long>(id - 1) * static_cast<long long>(parts) + static_cast<long long>(part) + 1;
  return run > std::numeric_limits<int>::max() ? -1 : static_cast<int>(run);
}

// The part and its own id behind run-wide id `run` (from 1).
inline PartFaultId part_fault_id(int run, std::size_t parts) {
  const auto n = static_cast<long long>(parts);
  const auto r = static_cast<long long>(run) - 1;
  return {static_cast<std::size_t>(r % n), static_cast<int>(r / n + 1)};
}

}  // namespace vdrive::control
