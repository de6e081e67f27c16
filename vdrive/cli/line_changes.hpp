#pragma once
// What changed on a served line between two status samples, as the lines `vdrive run` logs at
// info level (docs/cli.md "What run logs"): AL state changes, AL errors with the ETG text of their
// code, and drive alarms (603Fh) by the product's own name:
//   slave 2 @0x1002 ds5c1: Pre-Op -> Safe-Op     (the address once the master has set it)
//   slave 2 @0x1002 ds5c1: AL error 0x001D Invalid output configuration, in Pre-Op
//   slave 1 @0x1001 a6b: alarm Err16.0 Overload (603Fh FF10h)
//   slave 1 @0x1001 a6b: alarm cleared
//   onward link down: the line ends at the last slave here      (`run --next-iface`)
// An AL error or alarm seen within runtime::kStallAftermath of a host stall ends "after a host
// stall of 12.3 ms". host_stall_lines() are the stalls themselves, logged at warning level.
// A change that comes and goes between two samples is not seen.
#include <cstddef>
#include <string>
#include <vector>

#include "vdrive/runtime/line_status.hpp"

namespace vdrive::network { class Network; }

namespace vdrive::cli {

// `slaves_before`: the slaves of the line before this process's (a later part of --processes), so
// slaves are named by their place in the whole line.
std::vector<std::string> line_changes(const runtime::StatusSample& before, const runtime::StatusSample& now,
                                      const network::Network& network, std::size_t slaves_before = 0);

// Each stall recorded since number `seen` (updated), as runtime::describe() says it; stalls the
// record ring no longer holds are counted in one line. `slaves_before`: as for line_changes().
std::vector<std::string> host_stall_lines(const runtime::HostStalls& stalls, std::uint64_t& seen, std::size_t slaves_before = 0);

}  // namespace vdrive::cli
