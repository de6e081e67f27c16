#include "vdrive/cli/veth_pair.hpp"

#include <fmt/core.h>
#include <linux/if_link.h>
#include <linux/netlink.h>
#include <linux/rtnetlink.h>
#include <linux/veth.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <span>
#include <vector>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/link/net_interface.hpp"

namespace vdrive::cli {

namespace {

// A netlink request under construction: header, ifinfomsg, then nested attributes.
class Request {
public:
  Request(std::uint16_t type, std::uint16_t flags) {
    buf_.resize(NLMSG_SPACE(sizeof(ifinfomsg)));
    auto* h = header();
    h->nlmsg_type = type;
    h->nlmsg_flags = static_cast<std::uint16_t>(NLM_F_REQUEST | NLM_F_ACK | flags);
    h->nlmsg_seq = 1;
    auto* ifi = reinterpret_cast<ifinfomsg*>(NLMSG_DATA(h));
    ifi->ifi_family = AF_UNSPEC;
    h->nlmsg_len = static_cast<std::uint32_t>(NLMSG_LENGTH(sizeof(ifinfomsg)));
  }
  // Appends an attribute; returns its offset so nested attributes can be closed with end().
  std::size_t add(std::uint16_t type, const void* data = nullptr, std::size_t len = 0) {
    const std::size_t at = NLMSG_ALIGN(header()->nlmsg_len);
    buf_.resize(at + RTA_SPACE(len));
    auto* rta = reinterpret_cast<rtattr*>(buf_.data() + at);
    rta->rta_type = type;
    rta->rta_len = static_cast<std::uint16_t>(RTA_LENGTH(len));
    if (len) std::memcpy(RTA_DATA(rta), data, len);
    header()->nlmsg_len = static_cast<std::uint32_t>(at + RTA_SPACE(len));
    return at;
  }
  void add_string(std::uint16_t type, const std::string& s) { add(type, s.c_str(), s.size() + 1); }
  // Raw bytes inside a nest (the peer's ifinfomsg).
  void add_raw(const void* data, std::size_t len) {
    const std::size_t at = NLMSG_ALIGN(header()->nlmsg_len);
    buf_.resize(at + NLMSG_ALIGN(len));
    std::memcpy(buf_.data() + at, data, len);
    header()->nlmsg_len = static_cast<std::uint32_t>(at + NLMSG_ALIGN(len));
  }
  void end(std::size_t nest) {
    reinterpret_cast<rtattr*>(buf_.data() + nest)->rta_len =
        static_cast<std::uint16_t>(header()->nlmsg_len - nest);
  }
  nlmsghdr* header() { return reinterpret_cast<nlmsghdr*>(buf_.data()); }
  std::span<const std::uint8_t> bytes() { return {buf_.data(), header()->nlmsg_len}; }

private:
  std::vector<std::uint8_t> buf_;
};

// Sends the request and returns the kernel's errno (0 = success).
int talk(Request& req) {
  const int fd = ::socket(AF_NETLINK, SOCK_RAW | SOCK_CLOEXEC, NETLINK_ROUTE);
  if (fd < 0) return errno;
  sockaddr_nl kernel{};
  kernel.nl_family = AF_NETLINK;
  int result = 0;
  const auto bytes = req.bytes();
  if (::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&kernel), sizeof kernel) < 0) {
    result = errno;
  } else {
    alignas(nlmsghdr) std::uint8_t reply[4096];
    const ssize_t n = ::recv(fd, reply, sizeof reply, 0);
    if (n < 0) {
      result = errno;
    } else {
      const auto* h = reinterpret_cast<const nlmsghdr*>(reply);
      if (NLMSG_OK(h, static_cast<std::uint32_t>(n)) && h->nlmsg_type == NLMSG_ERROR) {
        result = -reinterpret_cast<const nlmsgerr*>(NLMSG_DATA(h))->error;
      }
    }
  }
  ::close(fd);
  return result;
}

[[noreturn]] void fail(const std::string& what, int err) {
  if (err == EPERM || err == EACCES) {
    throw CliError(kExitNotPermitted, fmt::format("{}: {} (run as root)", what, std::strerror(err)));
  }
  throw CliError(kExitFailure, fmt::format("{}: {}", what, std::strerror(err)));
}

void delete_link(const std::string& name) {
  Request req(RTM_DELLINK, 0);
  req.add_string(IFLA_IFNAME, name);
  (void)talk(req);  // best effort: the pair may already be gone with its peer
}

}  // namespace

VethPair::VethPair(std::string master_end, std::string slave_end)
    : master_(std::move(master_end)), slave_(std::move(slave_end)) {
  link::net::check_interface_name(master_);
  link::net::check_interface_name(slave_);
  Request req(RTM_NEWLINK, NLM_F_CREATE | NLM_F_EXCL);
  req.add_string(IFLA_IFNAME, master_);
  const std::size_t linkinfo = req.add(IFLA_LINKINFO);
  req.add_string(IFLA_INFO_KIND, "veth");
  const std::size_t data = req.add(IFLA_INFO_DATA);
  const std::size_t peer = req.add(VETH_INFO_PEER);
  ifinfomsg peer_info{};
  peer_info.ifi_family = AF_UNSPEC;
  req.add_raw(&peer_info, sizeof peer_info);
  req.add_string(IFLA_IFNAME, slave_);
  req.end(peer);
  req.end(data);
  req.end(linkinfo);
  if (const int err = talk(req); err != 0) {
    if (err == EEXIST) {
      throw CliError(kExitFailure, fmt::format("cannot create veth pair {}/{}: an interface of that name exists "
                                               "(remove it, or choose another --suffix)", master_, slave_));
    }
    fail(fmt::format("cannot create veth pair {}/{}", master_, slave_), err);
  }
  try {
    link::net::set_interface_up(master_);
    link::net::set_interface_up(slave_);
  } catch (...) {
    delete_link(master_);
    throw;
  }
}

VethPair::~VethPair() { delete_link(master_); }

}  // namespace vdrive::cli
