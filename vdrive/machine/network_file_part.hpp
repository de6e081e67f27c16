#pragma once
// A network file's line cut into the parts of `vdrive run --processes N` (network::split_line):
// each part is a network file of its own slaves, numbered from the part's first, with the wires
// and named signals among them and the faults armed on them (faults on the master's wire go to
// part 1, whose port 0 that wire reaches). What cannot be cut is refused, naming where the file
// says it: a tree (branches that meet in one ESC), a wire between two parts (a wire is copied
// inside one process), a fault by station address (no part knows the addresses before the master
// sets them).
#include <cstddef>
#include <span>

#include "vdrive/machine/network_file.hpp"
#include "vdrive/network/line_parts.hpp"

namespace vdrive::machine {

// Throws NetworkFileError naming the first thing in `file` that cannot be cut as `parts` says.
void check_cut(const NetworkFile& file, std::span<const network::LinePart> parts);

// The part of the file's line that `part` names (a part check_cut accepted): its slaves numbered
// from its first; the master's wire faults go to the part that starts the line.
NetworkFile line_part(const NetworkFile& file, network::LinePart part);

}  // namespace vdrive::machine
