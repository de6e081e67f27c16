#pragma once
// A link carries whole Ethernet frames (destination MAC first, no FCS) between the master and the
// segment. Implementations: RawSocketLink (AF_PACKET on a named interface), TapLink (a TAP device),
// LoopbackLink (in-process pair, for tests and virtual time).
#include <cstddef>
#include <cstdint>
#include <span>

#include "common/clock.hpp"

namespace vdrive::link {

constexpr std::uint16_t kEtherTypeEtherCat = 0x88A4;
constexpr std::size_t kMaxFrame = 1518;  // without FCS; VLAN-tagged frames fit too

class Link {
public:
  virtual ~Link() = default;
  // Waits up to `timeout` (0 = poll, <0 = forever) for one EtherCAT frame and copies it into `buf`.
  // Returns its length, or 0 if none arrived. Non-EtherCAT traffic is discarded, never returned.
  virtual std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) = 0;
  // Sends one frame; frames shorter than 60 bytes are sent as they are (the kernel/NIC pads).
  // Returns false if the link refused it (link down, buffer full).
  virtual bool send(std::span<const std::uint8_t> frame) = 0;
  // A pollable file descriptor, or -1 for links that are not backed by one.
  virtual int fd() const { return -1; }
};

}  // namespace vdrive::link
