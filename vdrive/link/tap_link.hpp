#pragma once
// TapLink: the drive line behind a TAP device (/dev/net/tun, IFF_TAP | IFF_NO_PI). A master on
// the host opens the TAP interface like any NIC; every frame it sends there arrives here, and
// every frame we write appears on the interface as received.
//
// The device is created if absent (and then disappears when this link closes) or attached to
// if it already exists (e.g. made persistent with `ip tuntap add`), and is brought up.
// Semantics as RawSocketLink: only EtherCAT frames (EtherType 0x88A4, untagged) are returned,
// short frames are accepted, send() writes the frame as is. Needs root or CAP_NET_ADMIN.
#include <cstdint>
#include <string>
#include <vector>

#include "vdrive/link/link.hpp"
#include "vdrive/link/link_error.hpp"

namespace vdrive::link {

class TapLink final : public Link {
public:
  // Throws LinkError: NotPermitted, BadName (also: the name is a device that is not a TAP),
  // System (e.g. the TAP is in use by another process).
  explicit TapLink(const std::string& interface_name);
  ~TapLink() override;
  TapLink(const TapLink&) = delete;
  TapLink& operator=(const TapLink&) = delete;

  // Throws LinkError(NoInterface) once the device has been deleted (ip link del).
  std::size_t receive(std::span<std::uint8_t> buf, Nanos timeout) override;
  bool send(std::span<const std::uint8_t> frame) override;
  int fd() const override { return fd_; }
  PeekCost peek_cost() const override { return PeekCost::SystemCall; }  // a zero-timeout poll()
  bool frame_waiting() override;

  // The kernel's name for the device (as requested).
  const std::string& interface_name() const { return name_; }
  // Frames read from the device but not returned: not EtherCAT (the host's IPv6 neighbour
  // discovery and the like), too short, or longer than the caller's buffer.
  std::uint64_t discarded() const { return discarded_; }

private:
  std::string name_;
  int fd_ = -1;
  std::uint64_t discarded_ = 0;
  std::vector<std::uint8_t> overflow_;  // catches the tail of frames longer than the caller's buffer
};

}  // namespace vdrive::link
