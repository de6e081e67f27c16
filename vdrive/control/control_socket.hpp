#pragma once
// The runtime control channel's Unix-domain socket (SOCK_STREAM, one request line and one
// reply line per connection).
//
// Path: --control PATH, else $XDG_RUNTIME_DIR/vdrive/<iface>.sock, else /run/vdrive/<iface>.sock
// for root, else /tmp/vdrive-<uid>/<iface>.sock. The server creates a missing directory 0700
// and refuses one owned by another user (root's excepted); the socket is 0600, and each peer's
// uid is checked with SO_PEERCRED: only the server's own uid and root are served, others get a
// `denied` reply. A stale socket (nobody listening) is replaced; a live one is an error. The
// socket is removed when the server ends.
//
// ControlServer runs on its own thread and serves one connection at a time (a client that does
// not send its line within 2 s is dropped, a line over 64 KiB ends the connection); the handler
// runs on that thread. Requests over the bound of request_rate.hpp are answered `failed`, "too
// many requests", without reaching the handler.
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>

#include "common/clock.hpp"
#include "vdrive/control/request_rate.hpp"

namespace vdrive::control {

std::string default_control_path(std::string_view iface);

// A failure of the socket itself (not of a request); the message names the path.
class ControlSocketError : public std::runtime_error {
public:
  enum class Kind { no_server, not_permitted, failed };
  ControlSocketError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

private:
  Kind kind_;
};

class ControlServer {
public:
  // Request line -> reply line, for a permitted peer.
  using Handler = std::function<std::string(std::string_view line)>;
  // Reply line for a peer whose uid may not control this server.
  using Refuser = std::function<std::string(unsigned uid)>;

  // Binds and listens (throws ControlSocketError), then serves on a new thread.
  ControlServer(std::string path, Handler handler, Refuser refuser);
  ~ControlServer();  // stops the thread, removes the socket
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;

  const std::string& path() const { return path_; }

private:
  void run();
  void serve_one(int client);

  std::string path_;
  Handler handler_;
  Refuser refuser_;
  RequestRate rate_;
  int listen_fd_ = -1;
  int stop_fd_ = -1;  // eventfd: ends run()
  unsigned long inode_ = 0;  // the socket file we made, so we never remove another's
  std::thread thread_;
};

// Removes the socket file at `path` if nobody listens there (its server was killed before it could
// remove it); leaves a live one, or anything that is not a socket. Never throws.
void remove_if_stale(const std::string& path);

// One round trip: connects to `path`, sends `line`, returns the reply line. Throws
// ControlSocketError naming the path (no_server: nothing listens there).
std::string control_call(const std::string& path, std::string_view line, Nanos timeout);

}  // namespace vdrive::control
