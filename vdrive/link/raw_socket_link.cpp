#include "vdrive/link/raw_socket_link.hpp"

#include <arpa/inet.h>
#include <linux/if_ether.h>
#include <linux/if_packet.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <ctime>

#include "vdrive/link/net_interface.hpp"

namespace vdrive::link {

RawSocketLink::RawSocketLink(const std::string& interface_name, Options options)
    : name_(interface_name), busy_poll_(options.busy_poll < 0 ? 0 : options.busy_poll) {
  ifindex_ = net::interface_index(name_);
  if (!net::interface_is_up(name_)) {
    throw LinkError(LinkError::Kind::InterfaceDown,
                    "interface '" + name_ + "' is down (ip link set " + name_ + " up)");
  }

  // Protocol 0 at creation: the socket receives nothing until bind() names the interface and
  // EtherType, so no frame from another interface can slip in between.
  fd_ = ::socket(AF_PACKET, SOCK_RAW | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw net::error_from_errno("socket(AF_PACKET)", name_, errno);

  try {
    sockaddr_ll addr{};
    addr.sll_family = AF_PACKET;
    addr.sll_protocol = htons(kEtherTypeEtherCat);
    addr.sll_ifindex = ifindex_;
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0) {
      throw net::error_from_errno("bind", name_, errno);
    }

    packet_mreq mreq{};
    mreq.mr_ifindex = ifindex_;
    mreq.mr_type = PACKET_MR_PROMISC;
    if (::setsockopt(fd_, SOL_PACKET, PACKET_ADD_MEMBERSHIP, &mreq, sizeof mreq) < 0) {
      throw net::error_from_errno("PACKET_ADD_MEMBERSHIP", name_, errno);
    }

#ifdef PACKET_IGNORE_OUTGOING
    // Linux >= 4.20: the kernel does not even queue our own sends to us. receive() also checks
    // the packet type, so older kernels behave the same.
    int one = 1;
    (void)::setsockopt(fd_, SOL_PACKET, PACKET_IGNORE_OUTGOING, &one, sizeof one);
#endif
    if (options.qdisc_bypass) {
      int on = 1;
      // Best effort: an old kernel without it still works, only slower.
      (void)::setsockopt(fd_, SOL_PACKET, PACKET_QDISC_BYPASS, &on, sizeof on);
    }
    if (busy_poll_ > 0) {
      // Microseconds, for drivers with NAPI busy polling; elsewhere (veth) it is accepted and has
      // no effect, and without CAP_NET_ADMIN it may be refused: the spin in receive() still works.
      const int us = static_cast<int>(std::min<Nanos>(busy_poll_ / 1000 + 1, 1'000'000));
      (void)::setsockopt(fd_, SOL_SOCKET, SO_BUSY_POLL, &us, sizeof us);
    }
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

RawSocketLink::~RawSocketLink() {
  if (fd_ >= 0) ::close(fd_);
}

namespace {

Nanos monotonic_now() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<Nanos>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

std::size_t RawSocketLink::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  const net::ReceiveDeadline deadline(timeout);
  // The spin ends at the busy-poll window or the caller's timeout, whichever is first; 0: none.
  Nanos spin_until = 0;
  if (busy_poll_ > 0 && timeout != 0) {
    const Nanos window = timeout > 0 ? std::min(busy_poll_, timeout) : busy_poll_;
    spin_until = monotonic_now() + window;
  }
  for (;;) {
    sockaddr_ll from{};
    socklen_t from_len = sizeof from;
    // MSG_TRUNC: the return value is the frame's real length, so an oversize frame is detected
    // and discarded rather than passed on cut short.
    ssize_t n = ::recvfrom(fd_, buf.data(), buf.size(), MSG_TRUNC | MSG_DONTWAIT,
                           reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n >= 0) {
      if (from.sll_pkttype == PACKET_OUTGOING || from.sll_ifindex != ifindex_) continue;
      const auto len = static_cast<std::size_t>(n);
      if (len > buf.size() || !net::is_ethercat(buf.first(len))) {
        ++discarded_;
        continue;
      }
      return len;
    }
    if (errno == EINTR) return 0;  // let the caller look at its stop flag
    if (errno == ENETDOWN) {
      // Reported once when the interface goes down (it may come back: a cable pulled) or is
      // removed (it never comes back: this socket is dead, e.g. a USB NIC unplugged).
      if (::if_nametoindex(name_.c_str()) != static_cast<unsigned>(ifindex_)) {
        throw LinkError(LinkError::Kind::NoInterface, "interface '" + name_ + "' disappeared");
      }
      return 0;
    }
    if (errno != EAGAIN && errno != EWOULDBLOCK) return 0;
    if (spin_until != 0) {
      if (monotonic_now() < spin_until) continue;
      spin_until = 0;  // the window is over: sleep for the rest of the timeout
    }
    if (!deadline.wait(fd_)) return 0;
  }
}

bool RawSocketLink::send(std::span<const std::uint8_t> frame) {
  for (;;) {
    ssize_t n = ::send(fd_, frame.data(), frame.size(), 0);
    if (n == static_cast<ssize_t>(frame.size())) return true;
    if (n < 0 && errno == EINTR) continue;
    return false;  // ENETDOWN, ENOBUFS, EINVAL (shorter than an Ethernet header), ...
  }
}

}  // namespace vdrive::link
