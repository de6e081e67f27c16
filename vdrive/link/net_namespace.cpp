#include "vdrive/link/net_namespace.hpp"

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "vdrive/link/link_error.hpp"

namespace vdrive::link {
namespace {

LinkError error(const std::string& what, int err) {
  const bool denied = err == EPERM || err == EACCES;
  return LinkError(denied ? LinkError::Kind::NotPermitted : LinkError::Kind::System,
                   what + ": " + std::strerror(err) + (denied ? " (entering a network namespace needs root)" : ""));
}

}  // namespace

NetnsScope::NetnsScope(const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    throw LinkError(LinkError::Kind::BadName, "invalid network namespace name '" + name + "'");
  const int target = ::open(("/run/netns/" + name).c_str(), O_RDONLY | O_CLOEXEC);
  if (target < 0) {
    if (errno == ENOENT)
      throw LinkError(LinkError::Kind::BadName, "no network namespace '" + name + "' (ip netns add " + name + " makes one)");
    throw error("network namespace '" + name + "'", errno);
  }
  home_ = ::open("/proc/thread-self/ns/net", O_RDONLY | O_CLOEXEC);
  if (home_ < 0) {
    const int err = errno;
    ::close(target);
    throw error("this thread's network namespace", err);
  }
  if (::setns(target, CLONE_NEWNET) != 0) {
    const int err = errno;
    ::close(target);
    ::close(home_);
    throw error("entering network namespace '" + name + "'", err);
  }
  ::close(target);
}

NetnsScope::~NetnsScope() {
  // Going back cannot fail for a namespace we came from while holding its descriptor.
  (void)::setns(home_, CLONE_NEWNET);
  ::close(home_);
}

}  // namespace vdrive::link
