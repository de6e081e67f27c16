// Topology checks and the visiting order; see topology.hpp.
#include "vdrive/network/topology.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace vdrive::network {
namespace {

constexpr int kPorts = 4;

bool implemented(std::uint8_t descriptor, int port) { return ((descriptor >> (2 * port)) & 0x03) != 0; }

std::string implemented_ports(std::uint8_t descriptor) {
  std::string ports;
  for (int p = 0; p < kPorts; ++p)
    if (implemented(descriptor, p)) ports += (ports.empty() ? "" : ", ") + std::to_string(p);
  return ports.empty() ? "none" : ports;
}

// Users count slaves from 1.
int shown(int index) { return index + 1; }

[[noreturn]] void fail(int slave, const std::string& what) {
  throw std::invalid_argument(fmt::format("topology: slave {}: {}", shown(slave), what));
}

// A slave whose parents never reach the master: name the loop it runs into.
[[noreturn]] void fail_loop(const Topology& t, int start) {
  std::vector<int> seen_at(t.uplinks.size(), -1);
  std::vector<int> path;
  int s = start;
  while (seen_at[static_cast<std::size_t>(s)] < 0) {
    seen_at[static_cast<std::size_t>(s)] = static_cast<int>(path.size());
    path.push_back(s);
    s = t.uplinks[static_cast<std::size_t>(s)].parent;
  }
  std::string loop;
  for (std::size_t i = static_cast<std::size_t>(seen_at[static_cast<std::size_t>(s)]); i < path.size(); ++i) {
    const Uplink& u = t.uplinks[static_cast<std::size_t>(path[i])];
    loop += fmt::format("slave {} -> port {} of ", shown(path[i]), u.port);
  }
  loop += fmt::format("slave {}", shown(s));
  fail(start, "its cables never reach the master: they form a loop (" + loop + ")");
}

}  // namespace

Topology Topology::line(std::size_t slaves) {
  Topology t;
  t.uplinks.resize(slaves);
  for (std::size_t i = 1; i < slaves; ++i) t.uplinks[i] = Uplink{static_cast<int>(i) - 1, 1};
  return t;
}

bool is_line(const Topology& t) {
  for (std::size_t i = 0; i < t.uplinks.size(); ++i) {
    const Uplink& u = t.uplinks[i];
    const bool in_line = i == 0 ? u.parent == Uplink::kMaster : u.parent == static_cast<int>(i) - 1 && u.port == 1;
    if (!in_line) return false;
  }
  return true;
}

void validate(const Topology& t, std::span<const std::uint8_t> port_descriptors) {
  const std::size_t n = port_descriptors.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!implemented(port_descriptors[i], 0))
      fail(static_cast<int>(i), fmt::format("its ESC implements no port 0 (port descriptor 0x{:02X})", port_descriptors[i]));
  if (t.is_default_line()) {
    for (std::size_t i = 0; i + 1 < n; ++i)
      if (!implemented(port_descriptors[i], 1))
        fail(static_cast<int>(i + 1), fmt::format("in the line it hangs on port 1 of slave {}, which that ESC does not "
                                                  "implement (port descriptor 0x{:02X}: ports {})",
                                                  i + 1, port_descriptors[i], implemented_ports(port_descriptors[i])));
    return;
  }
  if (t.uplinks.size() != n)
    throw std::invalid_argument(fmt::format("topology: {} uplinks for {} slaves (one per slave, or none for a line)",
                                            t.uplinks.size(), n));

  // Which slave sits on each port: -1 free. The master's one port is user[n][0].
  std::vector<std::array<int, kPorts>> user(n + 1);
  for (auto& ports : user) ports.fill(-1);
  for (std::size_t i = 0; i < n; ++i) {
    const int slave = static_cast<int>(i);
    const Uplink& u = t.uplinks[i];
    if (u.parent == Uplink::kMaster) {
      if (user[n][0] >= 0)
        fail(slave, fmt::format("cabled to the master, but slave {} already is (the master has one port)", shown(user[n][0])));
      user[n][0] = slave;
      continue;
    }
    if (u.parent < 0 || u.parent >= static_cast<int>(n))
      fail(slave, fmt::format("cabled to slave {}, which does not exist (slaves 1..{}, or the master)", shown(u.parent), n));
    if (u.parent == slave) fail(slave, fmt::format("cabled to its own port {}", u.port));
    const std::uint8_t descriptor = port_descriptors[static_cast<std::size_t>(u.parent)];
    if (u.port == 0)
      fail(slave, fmt::format("cabled to port 0 of slave {}, which is that slave's own way in (use port 1, 2 or 3)",
                              shown(u.parent)));
    if (u.port < 1 || u.port >= kPorts)
      fail(slave, fmt::format("cabled to port {} of slave {}: there is no such port (1, 2 or 3)", u.port, shown(u.parent)));
    if (!implemented(descriptor, u.port))
      fail(slave, fmt::format("cabled to port {} of slave {}, which that ESC does not implement (port descriptor "
                              "0x{:02X}: ports {})",
                              u.port, shown(u.parent), descriptor, implemented_ports(descriptor)));
    int& taken = user[static_cast<std::size_t>(u.parent)][static_cast<std::size_t>(u.port)];
    if (taken >= 0)
      fail(slave, fmt::format("cabled to port {} of slave {}, where slave {} already is", u.port, shown(u.parent), shown(taken)));
    taken = slave;
  }
  // Every slave must lead to the master within n steps; one that does not runs into a loop.
  for (std::size_t i = 0; i < n; ++i) {
    int s = static_cast<int>(i);
    std::size_t steps = 0;
    while (s != Uplink::kMaster && steps++ <= n) s = t.uplinks[static_cast<std::size_t>(s)].parent;
    if (s != Uplink::kMaster) fail_loop(t, static_cast<int>(i));
  }
}

std::vector<std::size_t> visiting_order(const Topology& t, std::size_t slaves) {
  const Topology line = t.is_default_line() ? Topology::line(slaves) : Topology{};
  const Topology& topology = t.is_default_line() ? line : t;
  std::vector<std::array<int, kPorts>> child(slaves);
  for (auto& ports : child) ports.fill(-1);
  int root = -1;
  for (std::size_t i = 0; i < slaves; ++i) {
    const Uplink& u = topology.uplinks[i];
    if (u.parent == Uplink::kMaster) root = static_cast<int>(i);
    else child[static_cast<std::size_t>(u.parent)][static_cast<std::size_t>(u.port)] = static_cast<int>(i);
  }
  std::vector<std::size_t> order;
  // Depth first: a slave, then what hangs on its ports 3, 1, 2 in turn.
  const auto visit = [&](const auto& self, int s) -> void {
    order.push_back(static_cast<std::size_t>(s));
    for (const int p : kDownstreamPortOrder)
      if (const int c = child[static_cast<std::size_t>(s)][static_cast<std::size_t>(p)]; c >= 0) self(self, c);
  };
  if (root >= 0) visit(visit, root);
  return order;
}

}  // namespace vdrive::network
