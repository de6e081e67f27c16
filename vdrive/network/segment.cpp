// The cabled slaves: frame path through the tree, per-hop timing, links. See segment.hpp.
#include "vdrive/network/segment.hpp"

#include "ethercat/datagram.hpp"
#include "ethercat/registers.hpp"

namespace vdrive::network {
namespace {

constexpr std::size_t kMacBytes = 6;
constexpr std::size_t kEthernetHeader = 14;
constexpr std::size_t kVlanTag = 4;
constexpr std::uint16_t kEtherTypeVlan = 0x8100;
constexpr std::uint16_t kEtherTypeEtherCat = 0x88A4;
constexpr std::uint8_t kLocallyAdministered = 0x02;
constexpr int kPorts = 4;

std::uint16_t be16(const std::uint8_t* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }

// Offset of the EtherCAT header, or 0 if the frame is not EtherCAT.
std::size_t ethercat_payload(std::span<const std::uint8_t> frame) {
  if (frame.size() < kEthernetHeader) return 0;
  std::size_t type_at = 2 * kMacBytes;
  if (be16(&frame[type_at]) == kEtherTypeVlan) {
    type_at += kVlanTag;
    if (frame.size() < type_at + 2) return 0;
  }
  return be16(&frame[type_at]) == kEtherTypeEtherCat ? type_at + 2 : 0;
}

}  // namespace

Segment::Segment(Nanos hop_delay) : hop_delay_(hop_delay) {}

void Segment::append(esc::Esc& esc) {
  slaves_.push_back(&esc);
  cable(Topology{});
}

void Segment::set_topology(const Topology& topology) {
  std::vector<std::uint8_t> descriptors;
  for (const esc::Esc* esc : slaves_) descriptors.push_back(esc->peek(ecat::reg::kPortDescriptor));
  validate(topology, descriptors);
  cable(topology);
}

void Segment::cable(const Topology& topology) {
  const std::size_t n = slaves_.size();
  uplinks_ = topology.is_default_line() ? Topology::line(n).uplinks : topology.uplinks;
  children_.assign(n, {-1, -1, -1, -1});
  root_ = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const Uplink& u = uplinks_[i];
    if (u.parent == Uplink::kMaster) root_ = static_cast<std::int32_t>(i);
    else children_[static_cast<std::size_t>(u.parent)][static_cast<std::size_t>(u.port)] = static_cast<std::int32_t>(i);
  }
  cable_ok_.assign(n, 1);
  timings_.assign(n, esc::FrameTiming{});
  order_.assign(n, 0);
  walk_.assign(n, Walk{0, 0});
  update_links();
}

int Segment::cabled_at(std::size_t slave, int port) const {
  if (slave >= slaves_.size() || port < 0 || port >= kPorts) return -1;
  return port == 0 ? static_cast<int>(slave) : children_[slave][static_cast<std::size_t>(port)];
}

void Segment::set_cable(int after_slave, bool connected) {
  const long into = static_cast<long>(after_slave) + 1;
  if (into < 0 || into >= static_cast<long>(slaves_.size())) return;
  cable_ok_[static_cast<std::size_t>(into)] = connected ? 1 : 0;
  update_links();
}

bool Segment::cable_connected(int after_slave) const {
  const long into = static_cast<long>(after_slave) + 1;
  if (into < 0 || into >= static_cast<long>(slaves_.size())) return false;
  return cable_ok_[static_cast<std::size_t>(into)] != 0;
}

bool Segment::set_port_cable(std::size_t slave, int port, bool connected) {
  const int into = cabled_at(slave, port);
  if (into < 0) return false;
  cable_ok_[static_cast<std::size_t>(into)] = connected ? 1 : 0;
  update_links();
  return true;
}

bool Segment::port_cable_connected(std::size_t slave, int port) const {
  const int into = cabled_at(slave, port);
  return into >= 0 && cable_ok_[static_cast<std::size_t>(into)] != 0;
}

void Segment::update_links() {
  for (std::size_t i = 0; i < slaves_.size(); ++i) {
    esc::PortLinks links;
    links.port[0] = cable_ok_[i] != 0;
    for (int p = 1; p < kPorts; ++p) {
      const std::int32_t child = children_[i][static_cast<std::size_t>(p)];
      links.port[p] = child >= 0 && cable_ok_[static_cast<std::size_t>(child)] != 0;
    }
    slaves_[i]->set_links(links);
  }
}

std::size_t Segment::plan(Nanos rx_time) {
  std::size_t visited = 0;
  std::size_t depth = 0;
  Nanos t = rx_time;
  const auto enter = [&](std::uint32_t slave) {
    esc::FrameTiming& timing = timings_[slave];
    timing = esc::FrameTiming{};
    timing.port0_rx = t;
    order_[visited++] = slave;
    walk_[depth++] = Walk{slave, 0};
  };
  enter(static_cast<std::uint32_t>(root_));
  while (depth > 0) {
    Walk& here = walk_[depth - 1];
    bool descended = false;
    while (here.next < std::size(kDownstreamPortOrder) && !descended) {
      const int port = kDownstreamPortOrder[here.next++];
      const std::int32_t child = children_[here.slave][static_cast<std::size_t>(port)];
      if (child < 0 || !cable_ok_[static_cast<std::size_t>(child)] || !slaves_[here.slave]->port_forwards(port)) continue;
      t += hop_delay_;
      enter(static_cast<std::uint32_t>(child));  // `here` stays valid: walk_ never reallocates
      descended = true;
    }
    if (descended) continue;
    // Every downstream port done: the frame leaves through port 0 into its parent's port.
    const std::uint32_t done = here.slave;
    if (--depth > 0) {
      t += hop_delay_;
      timings_[walk_[depth - 1].slave].rx(uplinks_[done].port) = t;
    }
  }
  return visited;
}

void Segment::process_corrupted(std::span<const std::uint8_t> /*ethernet_frame*/, Nanos /*rx_time*/) {
  ++dropped_;
  if (slaves_.empty() || !cable_ok_[static_cast<std::size_t>(root_)]) return;
  const std::size_t visited = plan(0);
  for (std::size_t k = 0; k < visited; ++k) {
    const std::uint32_t s = order_[k];
    slaves_[s]->count_rx_error(0, /*forwarded=*/k > 0);
    for (int port = 1; port < kPorts; ++port)
      if (timings_[s].rx(port) >= 0) slaves_[s]->count_rx_error(port, /*forwarded=*/true);
  }
}

bool Segment::process(std::span<std::uint8_t> frame, Nanos rx_time) {
  const std::size_t payload = ethercat_payload(frame);
  if (payload == 0 || slaves_.empty() || !cable_ok_[static_cast<std::size_t>(root_)]) {
    ++dropped_;
    return false;
  }
  const std::size_t visited = plan(rx_time);

  const std::span<std::uint8_t> pdu = frame.subspan(payload);
  // A well-formed DLPDU frame is checked once for all ESCs (Esc::process_checked_frame);
  // anything else goes through each ESC's own check, which destroys or passes it.
  const std::size_t datagrams = ecat::dlpdu_datagrams(pdu);
  for (std::size_t k = 0; k < visited; ++k) {
    const std::uint32_t s = order_[k];
    const bool passed = datagrams != 0 ? slaves_[s]->process_checked_frame(pdu, datagrams, timings_[s])
                                       : slaves_[s]->process_frame(pdu, timings_[s]);
    if (!passed) {
      ++dropped_;
      return false;
    }
  }
  frame[kMacBytes] |= kLocallyAdministered;  // source MAC, set as the frame leaves the root's port 0
  return true;
}

}  // namespace vdrive::network
