// The cabled slaves: topology, cables and the port links they give each ESC. The frame's path is
// in segment_frame_path.cpp. See segment.hpp.
#include "vdrive/network/segment.hpp"

#include <stdexcept>
#include <string>

#include "ethercat/registers.hpp"

namespace vdrive::network {
namespace {

constexpr int kPorts = 4;

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
  branches_.assign(n, Branches{});
  for (std::size_t i = 0; i < n; ++i) {
    for (const int port : kDownstreamPortOrder) {
      const std::int32_t child = children_[i][static_cast<std::size_t>(port)];
      if (child >= 0) branches_[i].in_order[branches_[i].count++] = Branch{child, port};
    }
  }
  line_ = is_line(Topology{uplinks_});
  cable_ok_.assign(n, 1);
  timings_.assign(n, esc::FrameTiming{});
  order_.assign(n, 0);
  walk_.assign(n, Walk{0, 0});
  if (onward_slave_ >= 0) onward_slave_ = last_visited();
  update_links();
}

std::int32_t Segment::last_visited() const {
  return static_cast<std::int32_t>(visiting_order(Topology{uplinks_}, slaves_.size()).back());
}

void Segment::set_onward_port() {
  if (slaves_.empty()) throw std::invalid_argument("the line has no slave to go on from");
  const std::int32_t last = last_visited();
  const std::uint8_t descriptor = slaves_[static_cast<std::size_t>(last)]->peek(ecat::reg::kPortDescriptor);
  if (((descriptor >> 2) & 0x03) == 0)
    throw std::invalid_argument("slave " + std::to_string(last + 1) +
                                ", the last on the line, has no port 1 to go on from");
  onward_slave_ = last;
  update_links();
}

void Segment::set_onward_link(bool up) {
  onward_link_ = up;
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
    if (static_cast<std::int32_t>(i) == onward_slave_) links.port[1] = onward_link_;
    slaves_[i]->set_links(links);
  }
}

}  // namespace vdrive::network
