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

// What asking Link::frame_waiting() costs, so a caller can decide how often to ask.
enum class PeekCost {
  Unsupported,  // the link cannot tell: frame_waiting() is always false
  Free,         // a memory load (a receive ring, an in-process queue): ask as often as you like
  SystemCall,   // a non-blocking system call (about a microsecond): ask sparingly
};

class Link {
public:
  virtual ~Link() = default;
  // Waits up to `timeout` (0 = poll, <0 = forever) for one EtherCAT frame and copies it into `buf`.
  // Returns its length, or 0 if none arrived. Non-EtherCAT traffic is discarded, never returned.
  virtual std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) = 0;
  // Sends one frame; frames shorter than 60 bytes are sent as they are (the kernel/NIC pads).
  // Returns false if the link refused it (link down, buffer full).
  virtual bool send(std::span<const std::uint8_t> frame) = 0;
  // Whether receive(buf, 0) would find a frame now, without taking it: lets a busy loop let a
  // frame overtake other work (runtime::FrameOvertake). May say true for a frame that receive()
  // then discards (not EtherCAT, our own send); never false while an EtherCAT frame waits,
  // except where peek_cost() is Unsupported.
  virtual PeekCost peek_cost() const { return PeekCost::Unsupported; }
  virtual bool frame_waiting() { return false; }
  // A pollable file descriptor, or -1 for links that are not backed by one.
  virtual int fd() const { return -1; }
  // Whether the link has carrier (a cable plugged in, a veth peer up); links that cannot tell
  // say true.
  virtual bool carrier() { return true; }
  // Sends a frame on through the onward port, to the part of the line beyond this process
  // (runtime::OnwardLink); a link without one refuses it.
  virtual bool send_onward(std::span<const std::uint8_t> frame) { return frame.empty(); }
};

}  // namespace vdrive::link
