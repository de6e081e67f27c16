// The runtime control channel's Unix-domain socket. See control_socket.hpp.
#include "vdrive/control/control_socket.hpp"

#include <fmt/core.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "vdrive/control/control_protocol.hpp"

namespace vdrive::control {
namespace {

using Kind = ControlSocketError::Kind;
constexpr std::size_t kMaxLine = 64 * 1024;
constexpr int kClientTimeoutMs = 2000;

[[noreturn]] void fail(Kind kind, const std::string& what, int err) {
  throw ControlSocketError(kind, fmt::format("{}: {}", what, std::strerror(err)));
}

sockaddr_un address_of(const std::string& path) {
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof a.sun_path)
    throw ControlSocketError(Kind::failed, fmt::format("control socket path '{}' is empty or longer than {} bytes", path,
                                                       sizeof a.sun_path - 1));
  std::memcpy(a.sun_path, path.c_str(), path.size() + 1);
  return a;
}

std::string parent_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// The socket's directory: created 0700 if missing; an existing one must be a directory owned by
// us or root, so nobody else decides who may reach the socket.
void prepare_directory(const std::string& dir) {
  if (::mkdir(dir.c_str(), 0700) == 0) return;
  if (errno != EEXIST) fail(Kind::failed, fmt::format("cannot create control directory {}", dir), errno);
  struct stat st{};
  if (::lstat(dir.c_str(), &st) != 0) fail(Kind::failed, fmt::format("cannot stat {}", dir), errno);
  if (!S_ISDIR(st.st_mode)) throw ControlSocketError(Kind::failed, fmt::format("{} is not a directory", dir));
  if (st.st_uid != ::geteuid() && st.st_uid != 0)
    throw ControlSocketError(Kind::not_permitted, fmt::format("control directory {} belongs to uid {}, not to us", dir, st.st_uid));
}

int connect_to(const std::string& path) {
  const sockaddr_un a = address_of(path);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) fail(Kind::failed, "socket(AF_UNIX)", errno);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    const int err = errno;
    ::close(fd);
    errno = err;
    return -1;
  }
  return fd;
}

// A socket file left by a vdrive that died is removed; one somebody listens on is an error.
void remove_stale(const std::string& path) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) return;
  if (!S_ISSOCK(st.st_mode)) throw ControlSocketError(Kind::failed, fmt::format("{} exists and is not a socket", path));
  const int fd = connect_to(path);
  if (fd >= 0) {
    ::close(fd);
    throw ControlSocketError(Kind::failed, fmt::format("another vdrive already listens on {} (--control PATH picks another)", path));
  }
  ::unlink(path.c_str());
}

bool write_all(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n = ::send(fd, data.data(), data.size(), MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// Reads up to the first newline (not included). False on timeout, error, EOF first or overlong.
bool read_line(int fd, std::string& line, int timeout_ms) {
  char buf[4096];
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    const int r = ::poll(&p, 1, timeout_ms);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    line.append(buf, static_cast<std::size_t>(n));
    if (const std::size_t nl = line.find('\n'); nl != std::string::npos) {
      line.resize(nl);
      return true;
    }
    if (line.size() > kMaxLine) return false;
  }
}

}  // namespace

std::string default_control_path(std::string_view iface) {
  const std::string file = fmt::format("{}.sock", iface);
  if (const char* xdg = std::getenv("XDG_RUNTIME_DIR"); xdg != nullptr && *xdg != '\0')
    return fmt::format("{}/vdrive/{}", xdg, file);
  if (::geteuid() == 0) return "/run/vdrive/" + file;
  return fmt::format("/tmp/vdrive-{}/{}", ::geteuid(), file);
}

ControlServer::ControlServer(std::string path, Handler handler, Refuser refuser)
    : path_(std::move(path)), handler_(std::move(handler)), refuser_(std::move(refuser)) {
  const sockaddr_un a = address_of(path_);
  prepare_directory(parent_of(path_));
  remove_stale(path_);
  listen_fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) fail(Kind::failed, "socket(AF_UNIX)", errno);
  // 0600 from the start: no window in which the socket is open to others.
  const mode_t old_mask = ::umask(0177);
  const int bound = ::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a);
  const int bind_errno = errno;
  ::umask(old_mask);
  struct stat st{};
  if (bound != 0 || ::chmod(path_.c_str(), 0600) != 0 || ::stat(path_.c_str(), &st) != 0 || ::listen(listen_fd_, 8) != 0) {
    const int err = bound != 0 ? bind_errno : errno;
    ::close(listen_fd_);
    fail(err == EACCES || err == EPERM ? Kind::not_permitted : Kind::failed, fmt::format("cannot listen on {}", path_), err);
  }
  inode_ = st.st_ino;
  stop_fd_ = ::eventfd(0, EFD_CLOEXEC);
  if (stop_fd_ < 0) {
    const int err = errno;
    ::close(listen_fd_);
    ::unlink(path_.c_str());
    fail(Kind::failed, "eventfd", err);
  }
  thread_ = std::thread([this] { run(); });
}

ControlServer::~ControlServer() {
  const std::uint64_t one = 1;
  (void)!::write(stop_fd_, &one, sizeof one);
  if (thread_.joinable()) thread_.join();
  struct stat st{};
  if (::lstat(path_.c_str(), &st) == 0 && st.st_ino == inode_) ::unlink(path_.c_str());
  ::close(listen_fd_);
  ::close(stop_fd_);
}

void ControlServer::run() {
  for (;;) {
    pollfd p[2] = {{listen_fd_, POLLIN, 0}, {stop_fd_, POLLIN, 0}};
    if (::poll(p, 2, -1) < 0) continue;  // EINTR
    if (p[1].revents != 0) return;
    if ((p[0].revents & POLLIN) == 0) continue;
    const int client = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) continue;
    serve_one(client);
    ::close(client);
  }
}

void ControlServer::serve_one(int client) {
  ucred peer{};
  socklen_t len = sizeof peer;
  if (::getsockopt(client, SOL_SOCKET, SO_PEERCRED, &peer, &len) != 0) return;
  std::string line;
  if (!read_line(client, line, kClientTimeoutMs)) return;
  // The line is read (and ignored) first even from a refused peer, so its send cannot fail.
  const bool permitted = peer.uid == ::geteuid() || peer.uid == 0;
  std::string reply;
  Nanos wait = 0;
  try {
    if (permitted && !rate_.take(&wait))
      reply = format_reply(error_reply(ControlReply::Status::failed, rate_.refusal(wait)));
    else
      reply = permitted ? handler_(line) : refuser_(peer.uid);
  } catch (const std::exception&) {  // never let one request end the server (and vdrive)
    reply = R"({"ok":false,"status":"failed","error":"vdrive could not answer this request"})";
  }
  write_all(client, reply + "\n");
}

void remove_if_stale(const std::string& path) {
  try {
    remove_stale(path);
  } catch (const ControlSocketError&) {  // live, or not a socket: not ours to remove
  }
}

std::string control_call(const std::string& path, std::string_view line, Nanos timeout) {
  const int fd = connect_to(path);
  if (fd < 0) {
    const int err = errno;
    const Kind kind = err == EACCES || err == EPERM ? Kind::not_permitted
                      : err == ENOENT || err == ECONNREFUSED || err == ENOTDIR ? Kind::no_server
                                                                               : Kind::failed;
    fail(kind, fmt::format("cannot connect to {}{}", path, kind == Kind::no_server ? " (is vdrive run serving there?)" : ""), err);
  }
  std::string reply;
  const bool ok = write_all(fd, std::string(line) + "\n") &&
                  read_line(fd, reply, static_cast<int>(std::max<Nanos>(timeout / 1'000'000, 1)));
  ::close(fd);
  if (!ok) throw ControlSocketError(Kind::failed, fmt::format("no reply from {}", path));
  return reply;
}

}  // namespace vdrive::control
