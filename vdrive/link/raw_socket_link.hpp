#pragma once
// RawSocketLink: the drive line on a real (or veth) interface, through an AF_PACKET raw socket.
//
// - Bound to one interface with protocol ETH_P_ETHERCAT (0x88A4): the kernel delivers only
//   EtherCAT frames. VLAN-tagged EtherCAT is not supported (masters do not tag it in practice):
//   the kernel strips an 802.1Q tag before a protocol-bound socket sees the frame, without
//   telling it, so such a frame arrives (and is answered) untagged; QinQ is not received.
// - Promiscuous membership (PACKET_MR_PROMISC): masters send to broadcast or to any MAC, and a
//   real ESC accepts every destination and source MAC, so do we.
// - Our own transmissions (PACKET_OUTGOING) are never returned by receive().
// - Frames shorter than the 60-byte Ethernet minimum (veth does not pad) are accepted and
//   returned at their real length; send() writes a frame exactly as given.
// - No allocation after construction; receive() copies into the caller's buffer and waits with
//   ppoll(), so a timeout has nanosecond resolution; optionally it spins first (Options::busy_poll)
//   and takes frames from a ring shared with the kernel instead of recvfrom() (Options::rx_ring).
// Opening needs root or CAP_NET_RAW; failures throw LinkError naming the interface.
#include <cstdint>
#include <string>

#include "vdrive/link/link.hpp"
#include "vdrive/link/link_error.hpp"

struct sockaddr_ll;

namespace vdrive::link {

class RawSocketLink final : public Link {
public:
  struct Options {
    // PACKET_QDISC_BYPASS: hand sent frames straight to the driver (lower latency; frames bypass
    // tc/qdisc, so traffic shaping and `tc` captures on egress do not see them).
    bool qdisc_bypass = true;
    // Busy polling: when no frame is waiting, receive() keeps retrying a non-blocking read for up
    // to this long (never past its timeout) before it sleeps in ppoll(). A frame that arrives
    // within the window is picked up without a wake-up through the scheduler (tens of us on a
    // loaded host), at the price of a core spinning meanwhile. 0: sleep at once. Also sets
    // SO_BUSY_POLL to the same time where the driver supports NAPI busy polling (real NICs; veth
    // does not), best effort.
    Nanos busy_poll = 0;
    // PACKET_RX_RING (TPACKET_V2, 128 slots of 2 KiB, mapped once at construction): the kernel
    // writes each frame into a ring slot, and receive() takes it from there without a system call
    // (recvfrom is then only asked for the socket's error after a wake-up with an empty ring).
    // A frame is still copied once, into the caller's buffer. It also makes frame_waiting() a
    // memory load, so frames can overtake the firmware after every slave (FrameOvertake).
    // false: one recvfrom() per frame.
    bool rx_ring = true;
  };

  // Throws LinkError: NoInterface ("no interface 'X'"), NotPermitted, InterfaceDown, BadName,
  // System.
  explicit RawSocketLink(const std::string& interface_name) : RawSocketLink(interface_name, Options{}) {}
  RawSocketLink(const std::string& interface_name, Options options);
  ~RawSocketLink() override;
  RawSocketLink(const RawSocketLink&) = delete;
  RawSocketLink& operator=(const RawSocketLink&) = delete;

  // Throws LinkError(NoInterface, "interface 'X' disappeared") once the interface has been
  // removed: the socket can never receive again. An interface merely going down does not throw.
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override;
  bool send(std::span<const std::uint8_t> frame) override;
  int fd() const override { return fd_; }
  // IFF_RUNNING: the interface is up and has carrier (for a veth, its peer is up). A system call.
  bool carrier() override;
  // Free with the receive ring (a look at the next slot), a zero-timeout poll() without it.
  PeekCost peek_cost() const override { return ring_ != nullptr ? PeekCost::Free : PeekCost::SystemCall; }
  bool frame_waiting() override;

  const std::string& interface_name() const { return name_; }
  int interface_index() const { return ifindex_; }
  // Frames the kernel delivered but receive() discarded: longer than the caller's buffer, too
  // short for an Ethernet header, or not EtherCAT.
  std::uint64_t discarded() const { return discarded_; }

private:
  std::string name_;
  int ifindex_ = 0;
  int fd_ = -1;
  std::uint64_t discarded_ = 0;
  Nanos busy_poll_ = 0;
  // The RX ring (Options::rx_ring): mapped memory, its slot size and count, the next slot to read.
  std::uint8_t* ring_ = nullptr;
  std::size_t ring_bytes_ = 0;
  std::size_t slot_bytes_ = 0;
  std::size_t slots_ = 0;
  std::size_t next_slot_ = 0;

  void map_rx_ring();
  // The frame in the next ring slot, if the kernel has filled it: 1 = delivered into `buf`
  // (length in `len`), 0 = the slot is empty, -1 = a frame was skipped (the slot is returned).
  int take_from_ring(std::span<std::uint8_t> buf, std::size_t& len);
  bool keep(const sockaddr_ll& from, std::span<const std::uint8_t> captured, std::size_t length,
            std::size_t capacity);
  bool nothing_waiting(int err) const;
};

}  // namespace vdrive::link
