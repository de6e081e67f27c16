#include "vdrive/link/raw_socket_link.hpp"

#include <arpa/inet.h>
#include <linux/if_ether.h>
#include <linux/if_packet.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
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
    if (options.rx_ring) map_rx_ring();  // before bind: no frame can land outside the ring
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
    if (ring_ != nullptr) ::munmap(ring_, ring_bytes_);
    ::close(fd_);
    throw;
  }
}

RawSocketLink::~RawSocketLink() {
  if (ring_ != nullptr) ::munmap(ring_, ring_bytes_);
  if (fd_ >= 0) ::close(fd_);
}

void RawSocketLink::map_rx_ring() {
  int version = TPACKET_V2;
  if (::setsockopt(fd_, SOL_PACKET, PACKET_VERSION, &version, sizeof version) < 0) {
    throw net::error_from_errno("PACKET_VERSION", name_, errno);
  }
  // Slots of 2 KiB hold a full-size Ethernet frame behind the ring's header; two per page.
  constexpr unsigned kSlotBytes = 2048, kBlockBytes = 4096, kBlocks = 64;
  tpacket_req req{};
  req.tp_block_size = kBlockBytes;
  req.tp_block_nr = kBlocks;
  req.tp_frame_size = kSlotBytes;
  req.tp_frame_nr = kBlocks * (kBlockBytes / kSlotBytes);
  if (::setsockopt(fd_, SOL_PACKET, PACKET_RX_RING, &req, sizeof req) < 0) {
    throw net::error_from_errno("PACKET_RX_RING", name_, errno);
  }
  const std::size_t bytes = std::size_t{kBlockBytes} * kBlocks;
  void* ring = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
  if (ring == MAP_FAILED) throw net::error_from_errno("mmap(PACKET_RX_RING)", name_, errno);
  ring_ = static_cast<std::uint8_t*>(ring);
  ring_bytes_ = bytes;
  slot_bytes_ = kSlotBytes;
  slots_ = req.tp_frame_nr;
}

bool RawSocketLink::frame_waiting() {
  if (ring_ == nullptr) return net::wait_readable(fd_, 0);
  const auto* hdr = reinterpret_cast<const tpacket2_hdr*>(ring_ + next_slot_ * slot_bytes_);
  return (__atomic_load_n(&hdr->tp_status, __ATOMIC_ACQUIRE) & TP_STATUS_USER) != 0;
}

int RawSocketLink::take_from_ring(std::span<std::uint8_t> buf, std::size_t& len) {
  auto* slot = ring_ + next_slot_ * slot_bytes_;
  auto* hdr = reinterpret_cast<tpacket2_hdr*>(slot);
  // The kernel hands the slot over with a release store of its status.
  if ((__atomic_load_n(&hdr->tp_status, __ATOMIC_ACQUIRE) & TP_STATUS_USER) == 0) return 0;
  const auto* from = reinterpret_cast<const sockaddr_ll*>(slot + TPACKET_ALIGN(sizeof(tpacket2_hdr)));
  const std::span<const std::uint8_t> captured(slot + hdr->tp_mac, hdr->tp_snaplen);  // a slot may cut it
  int result = -1;
  if (keep(*from, captured, hdr->tp_len, buf.size())) {
    std::memcpy(buf.data(), captured.data(), captured.size());
    len = captured.size();
    result = 1;
  }
  __atomic_store_n(&hdr->tp_status, TP_STATUS_KERNEL, __ATOMIC_RELEASE);
  next_slot_ = (next_slot_ + 1) % slots_;
  return result;
}

namespace {

Nanos monotonic_now() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<Nanos>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace

// Skips our own sends and other interfaces' frames; counts as discarded (not cut short) a frame
// longer than `capacity` or than what was captured of it, or one that is not EtherCAT.
bool RawSocketLink::keep(const sockaddr_ll& from, std::span<const std::uint8_t> captured, std::size_t length,
                         std::size_t capacity) {
  if (from.sll_pkttype == PACKET_OUTGOING || from.sll_ifindex != ifindex_) return false;
  if (length > capacity || captured.size() < length || !net::is_ethercat(captured)) {
    ++discarded_;
    return false;
  }
  return true;
}

// What receive() does with a failed recvfrom(): true for "nothing waiting" (go on waiting).
// Throws once the interface has been removed.
bool RawSocketLink::nothing_waiting(int err) const {
  if (err == ENETDOWN) {
    // Reported once when the interface goes down (it may come back: a cable pulled) or is
    // removed (it never comes back: this socket is dead, e.g. a USB NIC unplugged).
    if (::if_nametoindex(name_.c_str()) != static_cast<unsigned>(ifindex_)) {
      throw LinkError(LinkError::Kind::NoInterface, "interface '" + name_ + "' disappeared");
    }
    return false;
  }
  // Anything else returns (EINTR too: the caller looks at its stop flag).
  return err == EAGAIN || err == EWOULDBLOCK;
}

std::size_t RawSocketLink::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  const net::ReceiveDeadline deadline(timeout);
  // The spin ends at the busy-poll window or the caller's timeout, whichever is first; 0: none.
  Nanos spin_until = 0;
  if (busy_poll_ > 0 && timeout != 0) {
    const Nanos window = timeout > 0 ? std::min(busy_poll_, timeout) : busy_poll_;
    spin_until = monotonic_now() + window;
  }
  bool woken = false;  // ring: the last wait ended before its time
  for (;;) {
    if (ring_ != nullptr) {
      std::size_t len = 0;
      const int taken = take_from_ring(buf, len);
      if (taken > 0) return len;
      if (taken < 0) continue;
      if (woken) {  // readable but the ring is empty: the socket has an error to report
        woken = false;
        std::uint8_t probe = 0;
        if (::recv(fd_, &probe, 1, MSG_DONTWAIT) < 0 && !nothing_waiting(errno)) return 0;
      }
    } else {
      sockaddr_ll from{};
      socklen_t from_len = sizeof from;
      // MSG_TRUNC: the return value is the frame's real length, so an oversize frame is detected
      // and discarded rather than passed on cut short.
      ssize_t n = ::recvfrom(fd_, buf.data(), buf.size(), MSG_TRUNC | MSG_DONTWAIT,
                             reinterpret_cast<sockaddr*>(&from), &from_len);
      if (n >= 0) {
        const auto len = static_cast<std::size_t>(n);
        if (!keep(from, buf.first(std::min(len, buf.size())), len, buf.size())) continue;
        return len;
      }
      if (!nothing_waiting(errno)) return 0;
    }
    if (spin_until != 0) {
      if (monotonic_now() < spin_until) continue;
      spin_until = 0;  // the window is over: sleep for the rest of the timeout
    }
    if (!deadline.wait(fd_)) return 0;
    woken = true;
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

bool RawSocketLink::carrier() {
  ifreq req{};
  std::memcpy(req.ifr_name, name_.data(), std::min(name_.size(), sizeof req.ifr_name - 1));
  if (::ioctl(fd_, SIOCGIFFLAGS, &req) < 0) return false;
  return (req.ifr_flags & IFF_UP) != 0 && (req.ifr_flags & IFF_RUNNING) != 0;
}

}  // namespace vdrive::link
