#include "vdrive/link/tap_link.hpp"

#include <fcntl.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <sys/ioctl.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "vdrive/link/net_interface.hpp"

namespace vdrive::link {
namespace {

constexpr std::size_t kMaxTapFrame = 65536;  // a TAP device's MTU cannot exceed this

}  // namespace

TapLink::TapLink(const std::string& interface_name)
    : name_(interface_name), overflow_(kMaxTapFrame) {
  net::check_interface_name(name_);
  fd_ = ::open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    int err = errno;
    if (err == EPERM || err == EACCES) {
      throw LinkError(LinkError::Kind::NotPermitted,
                      "TAP devices need root or CAP_NET_ADMIN (/dev/net/tun: " +
                          std::string(std::strerror(err)) + ")");
    }
    throw net::error_from_errno("open /dev/net/tun", name_, err);
  }
  try {
    ifreq req{};
    req.ifr_flags = IFF_TAP | IFF_NO_PI;
    std::memcpy(req.ifr_name, name_.data(), name_.size());
    if (::ioctl(fd_, TUNSETIFF, &req) < 0) {
      int err = errno;
      if (err == EPERM || err == EACCES) {
        throw LinkError(LinkError::Kind::NotPermitted,
                        "TAP devices need root or CAP_NET_ADMIN (TUNSETIFF '" + name_ + "': " +
                            std::strerror(err) + ")");
      }
      if (err == EINVAL) {  // the name belongs to a device that is not a TAP (a NIC, veth, TUN)
        throw LinkError(LinkError::Kind::BadName,
                        "'" + name_ + "' exists and is not a TAP device");
      }
      if (err == EBUSY) {
        throw LinkError(LinkError::Kind::System,
                        "TAP device '" + name_ + "' is in use by another process");
      }
      throw net::error_from_errno("TUNSETIFF", name_, err);
    }
    net::set_interface_up(name_);
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

TapLink::~TapLink() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t TapLink::receive(std::span<std::uint8_t> buf, Nanos timeout) {
  const net::ReceiveDeadline deadline(timeout);
  for (;;) {
    // One read() returns one whole frame; the second iovec makes an oversize frame visible
    // (the total exceeds the caller's buffer) instead of silently truncating it.
    iovec iov[2] = {{buf.data(), buf.size()}, {overflow_.data(), overflow_.size()}};
    ssize_t n = ::readv(fd_, iov, 2);
    if (n >= 0) {
      const auto len = static_cast<std::size_t>(n);
      if (len > buf.size() || !net::is_ethercat(buf.first(len))) {
        ++discarded_;
        continue;
      }
      return len;
    }
    if (errno == EINTR) return 0;
    if (errno == EBADFD) {  // the device was deleted under us (ip link del): the fd is dead
      throw LinkError(LinkError::Kind::NoInterface, "TAP device '" + name_ + "' disappeared");
    }
    if (errno != EAGAIN && errno != EWOULDBLOCK) return 0;
    if (!deadline.wait(fd_)) return 0;
  }
}

bool TapLink::frame_waiting() { return net::wait_readable(fd_, 0); }

bool TapLink::send(std::span<const std::uint8_t> frame) {
  for (;;) {
    ssize_t n = ::write(fd_, frame.data(), frame.size());
    if (n == static_cast<ssize_t>(frame.size())) return true;
    if (n < 0 && errno == EINTR) continue;
    return false;  // EIO while the interface is down, EAGAIN when the host side is not reading
  }
}

}  // namespace vdrive::link
