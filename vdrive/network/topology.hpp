#pragma once
// Topology: how the slaves of one link are cabled. Every slave's port 0 (EtherCAT IN) is cabled
// either to the master or to port 1, 2 or 3 of another slave, so the slaves form a tree whose
// root is the slave cabled to the master. A frame walks the tree depth first, in each ESC's port
// order 0 -> 3 -> 1 -> 2 -> 0 (Segment, docs/topology.md).
//
// Slaves are numbered as Network::esc(i) and Segment::slave(i) number them: 0-based, in the order
// they were given (a network file's order). That order need not be the order the frame visits
// them, which is what a master counts as positions; visiting_order() gives that. Messages name
// slaves 1-based, as users count them everywhere else ("slave 1" is the first).
//
// An empty Topology is the line: slave i's port 1 to slave i+1's port 0, slave 0 to the master.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vdrive::network {

// Where one slave's port 0 is cabled.
struct Uplink {
  static constexpr int kMaster = -1;
  int parent = kMaster;  // 0-based slave index, or kMaster
  int port = 1;          // the parent's port (1, 2 or 3); unused when the parent is the master
};

struct Topology {
  std::vector<Uplink> uplinks;  // one per slave; empty: the line

  bool is_default_line() const { return uplinks.empty(); }
  // The line spelled out: slave 0 to the master, slave i to port 1 of slave i-1.
  static Topology line(std::size_t slaves);
};

// Throws std::invalid_argument, naming the slave and port, unless `topology` can be cabled:
// one uplink per slave (or none: the line); exactly one slave on the master; every parent an
// existing slave other than itself; every parent port 1..3 and implemented in the parent ESC's
// port descriptor (0x0007: 2 bits per port, 00 = not implemented); no port used twice; no loop
// (every slave leads back to the master). `port_descriptors` holds each slave's 0x0007.
void validate(const Topology& topology, std::span<const std::uint8_t> port_descriptors);

// Whether `topology` is the line (empty, or spelled out: slave 0 on the master, slave i on port 1
// of slave i-1).
bool is_line(const Topology& topology);

// The slaves in the order a frame visits them with every cable connected and every port open:
// position k (auto-increment address -k) is slave visiting_order(...)[k]. `topology` must be valid.
std::vector<std::size_t> visiting_order(const Topology& topology, std::size_t slaves);

// The ESC's port order after port 0: a frame leaves through 3, then 1, then 2, then back out of 0.
inline constexpr int kDownstreamPortOrder[3] = {3, 1, 2};

}  // namespace vdrive::network
