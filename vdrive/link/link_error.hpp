#pragma once
// Why a real link (raw socket, TAP) could not be opened, as a kind the command line maps to an
// exit code, plus a message a user can act on (what() names the interface).
#include <stdexcept>
#include <string>

namespace vdrive::link {

class LinkError : public std::runtime_error {
public:
  enum class Kind {
    NoInterface,     // the named interface does not exist
    InterfaceDown,   // it exists but is administratively down
    NotPermitted,    // EPERM/EACCES: raw sockets and TAP need root or CAP_NET_RAW/CAP_NET_ADMIN
    BadName,         // not a usable interface name (empty, too long)
    System,          // anything else the kernel refused; what() carries strerror
  };
  LinkError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

private:
  Kind kind_;
};

}  // namespace vdrive::link
