#include "vdrive/link/net_interface.hpp"

#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

namespace vdrive::link::net {
namespace {

// An AF_INET datagram socket is the conventional handle for SIOC[GS]IFFLAGS; it needs no
// privileges to read flags.
class IoctlSocket {
public:
  IoctlSocket() : fd_(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {
    if (fd_ < 0) throw error_from_errno("socket", "", errno);
  }
  ~IoctlSocket() { ::close(fd_); }
  IoctlSocket(const IoctlSocket&) = delete;
  IoctlSocket& operator=(const IoctlSocket&) = delete;
  int fd() const { return fd_; }

private:
  int fd_;
};

ifreq request_for(const std::string& name) {
  check_interface_name(name);
  ifreq req{};
  std::memcpy(req.ifr_name, name.data(), name.size());
  return req;
}

}  // namespace

void check_interface_name(const std::string& name) {
  bool ok = !name.empty() && name.size() < IFNAMSIZ && name != "." && name != "..";
  for (char c : name) {
    if (c == '/' || c == ':' || c == ' ' || c == '\t' || c == '\n') ok = false;
  }
  if (!ok) throw LinkError(LinkError::Kind::BadName, "invalid interface name '" + name + "'");
}

int interface_index(const std::string& name) {
  check_interface_name(name);
  unsigned index = ::if_nametoindex(name.c_str());
  if (index == 0) throw error_from_errno("if_nametoindex", name, errno);
  return static_cast<int>(index);
}

bool interface_is_up(const std::string& name) {
  ifreq req = request_for(name);
  IoctlSocket sock;
  if (::ioctl(sock.fd(), SIOCGIFFLAGS, &req) < 0) throw error_from_errno("SIOCGIFFLAGS", name, errno);
  return (req.ifr_flags & IFF_UP) != 0;
}

void set_interface_up(const std::string& name) {
  ifreq req = request_for(name);
  IoctlSocket sock;
  if (::ioctl(sock.fd(), SIOCGIFFLAGS, &req) < 0) throw error_from_errno("SIOCGIFFLAGS", name, errno);
  if (req.ifr_flags & IFF_UP) return;
  req.ifr_flags = static_cast<short>(req.ifr_flags | IFF_UP);
  if (::ioctl(sock.fd(), SIOCSIFFLAGS, &req) < 0) throw error_from_errno("SIOCSIFFLAGS", name, errno);
}

void set_interface_down(const std::string& name) {
  ifreq req = request_for(name);
  IoctlSocket sock;
  if (::ioctl(sock.fd(), SIOCGIFFLAGS, &req) < 0) throw error_from_errno("SIOCGIFFLAGS", name, errno);
  if ((req.ifr_flags & IFF_UP) == 0) return;
  req.ifr_flags = static_cast<short>(req.ifr_flags & ~IFF_UP);
  if (::ioctl(sock.fd(), SIOCSIFFLAGS, &req) < 0) throw error_from_errno("SIOCSIFFLAGS", name, errno);
}

LinkError error_from_errno(const std::string& call, const std::string& name, int err) {
  using Kind = LinkError::Kind;
  switch (err) {
    case EPERM:
    case EACCES:
      return LinkError(Kind::NotPermitted,
                       "raw sockets need root or CAP_NET_RAW (" + call + " on '" + name + "': " +
                           std::strerror(err) + ")");
    case ENODEV:
    case ENXIO:
      return LinkError(Kind::NoInterface, "no interface '" + name + "'");
    case ENETDOWN:
      return LinkError(Kind::InterfaceDown, "interface '" + name + "' is down");
    default:
      return LinkError(Kind::System, call + (name.empty() ? "" : " on '" + name + "'") + ": " +
                                         std::strerror(err));
  }
}

bool wait_readable(int fd, Nanos timeout) {
  pollfd pfd{fd, POLLIN, 0};
  timespec ts{};
  timespec* tsp = nullptr;
  if (timeout >= 0) {
    ts.tv_sec = static_cast<time_t>(timeout / 1'000'000'000);
    ts.tv_nsec = static_cast<long>(timeout % 1'000'000'000);
    tsp = &ts;
  }
  // EINTR (a signal, e.g. SIGTERM setting the stop flag) counts as "nothing arrived".
  int r = ::ppoll(&pfd, 1, tsp, nullptr);
  return r > 0 && (pfd.revents & (POLLIN | POLLERR)) != 0;
}

namespace {
// Monotonic now for timeout bookkeeping inside receive(); a link waits in real time by nature.
Nanos wall_now() {
  static const MonotonicClock clock;
  return clock.now();
}
}  // namespace

ReceiveDeadline::ReceiveDeadline(Nanos timeout)
    : timeout_(timeout), deadline_(timeout > 0 ? wall_now() + timeout : 0) {}

bool ReceiveDeadline::wait(int fd) const {
  if (timeout_ == 0) return false;
  Nanos remaining = -1;
  if (timeout_ > 0) {
    remaining = deadline_ - wall_now();
    if (remaining <= 0) return false;
  }
  return wait_readable(fd, remaining);
}

bool is_ethercat(std::span<const std::uint8_t> frame) {
  constexpr std::size_t kEthHeader = 14;
  return frame.size() >= kEthHeader &&
         ((static_cast<std::uint16_t>(frame[12]) << 8) | frame[13]) == kEtherTypeEtherCat;
}

}  // namespace vdrive::link::net
