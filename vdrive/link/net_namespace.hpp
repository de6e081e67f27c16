#pragma once
// NetnsScope: the calling thread inside a network namespace, named as `ip netns` names them
// (/run/netns/NAME), until the scope ends and the thread returns to the namespace it came from.
// A socket opened meanwhile stays bound to the namespace it was opened in, so a program can serve
// an interface inside a namespace while its other sockets (control, DDS, the web page) stay where
// its user is (`vdrive run --netns`). Only the calling thread moves; threads started inside the
// scope start inside the namespace. Needs CAP_SYS_ADMIN (root).
#include <string>

namespace vdrive::link {

class NetnsScope {
public:
  // Throws LinkError: BadName "no network namespace 'X' (ip netns add X makes one)", NotPermitted,
  // System.
  explicit NetnsScope(const std::string& name);
  ~NetnsScope();
  NetnsScope(const NetnsScope&) = delete;
  NetnsScope& operator=(const NetnsScope&) = delete;

private:
  int home_ = -1;
};

}  // namespace vdrive::link
