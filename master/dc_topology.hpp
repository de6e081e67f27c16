#pragma once
// Where each slave hangs and how far it is from the first, from what every ESC shows a master after
// one frame latched the receive times (0x0900-0x090F) and from its DL status (0x0110): as a
// master reconstructs a line or a tree (ETG.1000.4 frame order 0 -> 3 -> 1 -> 2). Each slave hangs
// on the next open port, in the order 3, 1, 2, of the nearest slave before it that has one left; a
// branch on port q of a parent was entered when the frame came back into the parent's previous open
// port (or at port 0), and half of the time until it came back into q, less the child's own
// branches, is the cable's share.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vdrive::master {

// What a master reads of one slave, by position.
struct PortTimes {
  std::uint16_t dl_status = 0;           // 0x0110
  std::array<std::uint32_t, 4> rx{};     // 0x0900 + 4 * port: receive time at each port
};

struct DcTopology {
  std::vector<std::size_t> parent;       // by position; the first slave is its own parent
  std::vector<int> parent_port;          // the parent's port (0 for the first slave)
  std::vector<std::int64_t> delay;       // propagation delay from the first slave, ns
};

// A port in use: loop open and communication established (DL status bits 8+2p, 9+2p = 0, 1).
bool port_in_use(const PortTimes& s, int port);

DcTopology compute_dc_topology(const std::vector<PortTimes>& slaves);

}  // namespace vdrive::master
