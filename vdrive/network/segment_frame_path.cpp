// The frame's path through the cabled slaves and its timing (segment.hpp): a tree walk that
// plans the path before any ESC processes the frame, and the line's own walk, which needs none
// of the tree's bookkeeping (the common case: every built-in product has two ports).
#include "vdrive/network/segment.hpp"

#include "ethercat/datagram.hpp"

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

std::size_t Segment::plan(Nanos rx_time, bool& onward) {
  onward = false;
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
    const Branches& branches = branches_[here.slave];
    while (here.next < branches.count && !descended) {
      const Branch& b = branches.in_order[here.next++];
      if (!cable_ok_[static_cast<std::size_t>(b.child)] || !slaves_[here.slave]->port_forwards(b.port)) continue;
      t += hop_delay_;
      enter(static_cast<std::uint32_t>(b.child));  // `here` stays valid: walk_ never reallocates
      descended = true;
    }
    if (descended) continue;
    if (static_cast<std::int32_t>(here.slave) == onward_slave_ && slaves_[here.slave]->port_forwards(1)) {
      // Out of this process: every port on the way back sees the frame when it returns.
      onward = true;
      timings_[here.slave].port1_rx = esc::FrameTiming::kLater;
      for (std::size_t d = depth - 1; d > 0; --d)
        timings_[walk_[d - 1].slave].rx(uplinks_[walk_[d].slave].port) = esc::FrameTiming::kLater;
      return visited;
    }
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
  bool onward = false;  // a corrupted frame goes on too, but nobody beyond can be told from here
  const std::size_t visited = plan(0, onward);
  for (std::size_t k = 0; k < visited; ++k) {
    const std::uint32_t s = order_[k];
    slaves_[s]->count_rx_error(0, /*forwarded=*/k > 0);
    for (int port = 1; port < kPorts; ++port)
      if (timings_[s].rx(port) >= 0) slaves_[s]->count_rx_error(port, /*forwarded=*/true);
  }
}

// In the line the frame turns at the first slave that does not forward out of port 1.
std::size_t Segment::line_turn() const {
  std::size_t turn = 0;
  while (turn + 1 < slaves_.size() && cable_ok_[turn + 1] && slaves_[turn]->port_forwards(1)) ++turn;
  return turn;
}

FrameExit Segment::route(std::span<std::uint8_t> frame, Nanos rx_time) {
  const std::size_t payload = ethercat_payload(frame);
  if (payload == 0 || slaves_.empty() || !cable_ok_[static_cast<std::size_t>(root_)]) {
    ++dropped_;
    return FrameExit::Destroyed;
  }
  const std::span<std::uint8_t> pdu = frame.subspan(payload);
  // A well-formed DLPDU frame is checked once for all ESCs (Esc::process_checked_frame);
  // anything else goes through each ESC's own check, which destroys or passes it.
  const std::size_t datagrams = ecat::dlpdu_datagrams(pdu);
  const auto pass = [&](std::size_t slave, const esc::FrameTiming& timing) {
    return datagrams != 0 ? slaves_[slave]->process_checked_frame(pdu, datagrams, timing)
                          : slaves_[slave]->process_frame(pdu, timing);
  };
  bool onward = false;
  if (line_) {
    const std::size_t turn = line_turn();
    onward = static_cast<std::int32_t>(turn) == onward_slave_ && slaves_[turn]->port_forwards(1);
    for (std::size_t i = 0; i <= turn; ++i) {
      esc::FrameTiming timing;
      timing.port0_rx = rx_time + static_cast<Nanos>(i) * hop_delay_;
      if (onward) timing.port1_rx = esc::FrameTiming::kLater;
      else if (i < turn) timing.port1_rx = rx_time + static_cast<Nanos>(2 * turn - i) * hop_delay_;
      if (!pass(i, timing)) {
        ++dropped_;
        return FrameExit::Destroyed;
      }
    }
  } else {
    const std::size_t visited = plan(rx_time, onward);
    for (std::size_t k = 0; k < visited; ++k) {
      if (!pass(order_[k], timings_[order_[k]])) {
        ++dropped_;
        return FrameExit::Destroyed;
      }
    }
  }
  if (onward) return FrameExit::Onward;
  frame[kMacBytes] |= kLocallyAdministered;  // source MAC, set as the frame leaves the root's port 0
  return FrameExit::ToMaster;
}

bool Segment::returned(std::span<std::uint8_t> frame, Nanos rx_time) {
  if (onward_slave_ < 0 || ethercat_payload(frame) == 0) return false;
  // Back up the tree from the onward port: each ESC on the way sees the frame at the port its
  // child hangs on, one hop later than the child.
  Nanos t = rx_time;
  std::int32_t child = onward_slave_;
  slaves_[static_cast<std::size_t>(child)]->frame_returned(1, t);
  for (;;) {
    const Uplink& up = uplinks_[static_cast<std::size_t>(child)];
    if (up.parent == Uplink::kMaster) break;
    t += hop_delay_;
    slaves_[static_cast<std::size_t>(up.parent)]->frame_returned(up.port, t);
    child = up.parent;
  }
  frame[kMacBytes] |= kLocallyAdministered;
  return true;
}

}  // namespace vdrive::network
