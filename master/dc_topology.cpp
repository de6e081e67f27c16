#include "master/dc_topology.hpp"

namespace vdrive::master {

bool port_in_use(const PortTimes& s, int port) { return ((s.dl_status >> (8 + 2 * port)) & 0x03) == 0x02; }

DcTopology compute_dc_topology(const std::vector<PortTimes>& seen) {
  DcTopology m;
  const std::size_t n = seen.size();
  m.parent.assign(n, 0);
  m.parent_port.assign(n, 0);
  m.delay.assign(n, 0);
  // 32-bit port times wrap: the signed difference is right as long as the round trip is short.
  const auto since = [](std::uint32_t later, std::uint32_t earlier) {
    return static_cast<std::int64_t>(static_cast<std::int32_t>(later - earlier));
  };
  const auto last_port = [&](std::size_t k) {
    int last = 0;
    for (const int p : {3, 1, 2})
      if (port_in_use(seen[k], p)) last = p;
    return last;
  };
  struct Open {
    std::size_t position;
    int previous;  // the port whose time says when the frame left through the next one
  };
  const auto next_port = [&](const Open& o) {
    bool after = o.previous == 0;
    for (const int p : {3, 1, 2}) {
      if (after && port_in_use(seen[o.position], p)) return p;
      after |= p == o.previous;
    }
    return -1;
  };
  if (n == 0) return m;
  std::vector<Open> open{{0, 0}};
  for (std::size_t k = 1; k < n; ++k) {
    while (!open.empty() && next_port(open.back()) < 0) open.pop_back();
    if (open.empty()) break;  // more slaves than open ports: not a tree the times can explain
    Open& p = open.back();
    const int q = next_port(p);
    const PortTimes& ps = seen[p.position];
    const std::int64_t left_parent = since(ps.rx[static_cast<std::size_t>(p.previous)], ps.rx[0]);
    const std::int64_t round_trip = since(ps.rx[static_cast<std::size_t>(q)], ps.rx[static_cast<std::size_t>(p.previous)]);
    const std::int64_t inside_child = since(seen[k].rx[static_cast<std::size_t>(last_port(k))], seen[k].rx[0]);
    m.parent[k] = p.position;
    m.parent_port[k] = q;
    m.delay[k] = m.delay[p.position] + left_parent + (round_trip - inside_child) / 2;
    p.previous = q;
    open.push_back({k, 0});
  }
  return m;
}

}  // namespace vdrive::master
