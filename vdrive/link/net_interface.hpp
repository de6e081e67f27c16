#pragma once
// Small Linux helpers shared by the real links (RawSocketLink, TapLink): interface lookup and
// flags through ioctl, errno -> LinkError, and waiting for a readable fd with a timeout.
#include <cstdint>
#include <span>
#include <string>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/link/link_error.hpp"

namespace vdrive::link::net {

// Throws LinkError(BadName) unless 1..15 characters without '/' or whitespace (IFNAMSIZ).
void check_interface_name(const std::string& name);
// Interface index; throws LinkError(NoInterface, "no interface 'X'").
int interface_index(const std::string& name);
// IFF_UP of the interface; throws LinkError like interface_index.
bool interface_is_up(const std::string& name);
// Sets IFF_UP; throws LinkError (NotPermitted without CAP_NET_ADMIN).
void set_interface_up(const std::string& name);
// Clears IFF_UP (a veth's peer then loses carrier); throws LinkError like set_interface_up.
void set_interface_down(const std::string& name);

// A LinkError for a failed system call `call` on interface `name` with errno `err`.
LinkError error_from_errno(const std::string& call, const std::string& name, int err);

// Waits until `fd` is readable or `timeout` elapsed (0 = just look, <0 = forever). Returns true
// if readable; false on timeout or when a signal interrupted the wait (so callers notice a stop
// request promptly).
bool wait_readable(int fd, Nanos timeout);

// The time left of a receive() timeout (0 = poll once, <0 = forever), for the fd-backed links.
class ReceiveDeadline {
public:
  explicit ReceiveDeadline(Nanos timeout);
  // Waits for `fd` to become readable within what is left; false when the time is up, or at once
  // for a poll.
  bool wait(int fd) const;

private:
  Nanos timeout_;
  Nanos deadline_;
};

// Untagged Ethernet frame with EtherType 0x88A4 (what a socket bound to 0x88A4 or a TAP hands us).
bool is_ethercat(std::span<const std::uint8_t> frame);

}  // namespace vdrive::link::net
