// The line of slaves: frame path, per-hop timing, links. See segment.hpp.
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
  cable_ok_.push_back(true);
  update_links();
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

void Segment::update_links() {
  for (std::size_t i = 0; i < slaves_.size(); ++i) {
    esc::PortLinks links;
    links.port[0] = cable_ok_[i] != 0;
    links.port[1] = i + 1 < slaves_.size() && cable_ok_[i + 1] != 0;
    slaves_[i]->set_links(links);
  }
}

// Where a frame turns back: the first slave that does not forward out of port 1.
std::size_t Segment::turning_slave() const {
  std::size_t turn = 0;
  while (turn + 1 < slaves_.size() && cable_ok_[turn + 1] && slaves_[turn]->port_forwards(1)) ++turn;
  return turn;
}

void Segment::process_corrupted(std::span<const std::uint8_t> /*ethernet_frame*/, Nanos /*rx_time*/) {
  ++dropped_;
  if (slaves_.empty() || !cable_ok_[0]) return;
  const std::size_t turn = turning_slave();
  constexpr int kPort0 = 0, kPort1 = 1;
  for (std::size_t i = 0; i <= turn; ++i) slaves_[i]->count_rx_error(kPort0, /*forwarded=*/i > 0);
  for (std::size_t i = turn; i-- > 0;) slaves_[i]->count_rx_error(kPort1, /*forwarded=*/true);
}

bool Segment::process(std::span<std::uint8_t> frame, Nanos rx_time) {
  const std::size_t payload = ethercat_payload(frame);
  if (payload == 0 || slaves_.empty() || !cable_ok_[0]) {
    ++dropped_;
    return false;
  }
  const std::size_t turn = turning_slave();

  const std::span<std::uint8_t> pdu = frame.subspan(payload);
  // A well-formed DLPDU frame is checked once for the whole line (Esc::process_checked_frame);
  // anything else goes through each ESC's own check, which destroys or passes it.
  const std::size_t datagrams = ecat::dlpdu_datagrams(pdu);
  for (std::size_t i = 0; i <= turn; ++i) {
    esc::FrameTiming timing;
    timing.port0_rx = rx_time + static_cast<Nanos>(i) * hop_delay_;
    if (i < turn) timing.port1_rx = rx_time + static_cast<Nanos>(2 * turn - i) * hop_delay_;
    const bool passed = datagrams != 0 ? slaves_[i]->process_checked_frame(pdu, datagrams, timing)
                                       : slaves_[i]->process_frame(pdu, timing);
    if (!passed) {
      ++dropped_;
      return false;
    }
  }
  frame[kMacBytes] |= kLocallyAdministered;  // source MAC, set as the frame leaves slave 1's port 0
  return true;
}

}  // namespace vdrive::network
