#include "vdrive/cli/part_processes.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <spdlog/spdlog.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <climits>
#include <cstring>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/exit_codes.hpp"
#include "vdrive/link/link_error.hpp"
#include "vdrive/link/net_interface.hpp"
#include "vdrive/link/net_namespace.hpp"

namespace vdrive::cli {
namespace {

std::string own_executable() {
  char path[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) throw CliError(kExitFailure, fmt::format("--processes: cannot find vdrive's own program: {}", std::strerror(errno)));
  return std::string(path, static_cast<std::size_t>(n));
}

std::string how_it_ended(int status) {
  if (WIFEXITED(status)) return fmt::format("exit code {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return fmt::format("killed by signal {} ({})", WTERMSIG(status), ::strsignal(WTERMSIG(status)));
  return "ended";
}

}  // namespace

namespace {

// Inside `netns` for as long as it lives; nothing without one.
std::unique_ptr<link::NetnsScope> inside(const std::string& netns) {
  if (netns.empty()) return nullptr;
  try {
    return std::make_unique<link::NetnsScope>(netns);
  } catch (const link::LinkError& e) {
    throw CliError(e.kind() == link::LinkError::Kind::NotPermitted ? kExitNotPermitted : kExitBadArguments,
                   fmt::format("--netns: {}", e.what()));
  }
}

}  // namespace

PartProcesses::PartProcesses(const std::vector<network::LinePart>& parts, const std::string& veth_prefix,
                             const std::string& netns, const ArgsOf& child_args)
    : parts_(parts), netns_(netns), children_(std::make_unique<Child[]>(parts.size())) {
  {
    const std::unique_ptr<link::NetnsScope> here = inside(netns_);
    try {
      for (std::size_t k = 0; k + 1 < parts.size(); ++k)
        veths_.push_back(std::make_unique<VethPair>(veth_prefix + std::to_string(k + 1) + "o", veth_prefix + std::to_string(k + 1) + "i"));
    } catch (...) {
      veths_.clear();  // inside the namespace still
      throw;
    }
  }
  // The children start here, outside the namespace: they open their interfaces in it themselves
  // (--netns in their arguments), and their control sockets, telemetry and pages stay where the
  // user is, as part 1's do.
  try {
    for (std::size_t k = 1; k < parts.size(); ++k) {
      const std::string& in = veths_[k - 1]->slave_end();
      const std::string next = k < veths_.size() ? veths_[k]->master_end() : std::string{};
      start(k, child_args(k, in, next));
    }
  } catch (...) {
    stop_children();
    try {
      const std::unique_ptr<link::NetnsScope> here = inside(netns_);
      veths_.clear();
    } catch (const CliError& e) {
      spdlog::warn("{}: the veth pairs of --processes stay", e.what());
    }
    throw;
  }
  watcher_ = std::thread([this] { watch(); });
}

PartProcesses::~PartProcesses() {
  stopping_.store(true);
  stop_children();
  if (watcher_.joinable()) watcher_.join();
  try {
    const std::unique_ptr<link::NetnsScope> here = inside(netns_);
    veths_.clear();
  } catch (const CliError& e) {
    spdlog::warn("{}: the veth pairs of --processes stay", e.what());
  }
}

std::string PartProcesses::name(std::size_t part) const {
  return network::part_name(part, parts_[part]);
}

void PartProcesses::start(std::size_t part, const std::vector<std::string>& args) {
  int ready[2];
  if (::pipe2(ready, O_CLOEXEC) != 0) throw CliError(kExitFailure, fmt::format("--processes: pipe: {}", std::strerror(errno)));
  std::vector<std::string> argv_text{own_executable()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  argv_text.push_back("--ready-fd");
  argv_text.push_back(std::to_string(ready[1]));
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log_name = fmt::format("VDRIVE_LOG_NAME=part {}", part + 1);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(ready[0]);
    ::close(ready[1]);
    throw CliError(kExitFailure, fmt::format("--processes: fork: {}", std::strerror(errno)));
  }
  if (pid == 0) {
    // Only async-signal-safe calls until exec.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    ::setpgid(0, 0);  // a terminal's Ctrl-C reaches the parent, which stops the parts in order
    if (::getppid() != parent) ::_exit(127);
    ::fcntl(ready[1], F_SETFD, 0);
    ::putenv(const_cast<char*>(log_name.c_str()));
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(ready[1]);
  children_[part].pid = pid;
  pollfd fd{ready[0], POLLIN, 0};
  const int r = ::poll(&fd, 1, static_cast<int>(std::chrono::milliseconds(kStartTimeout).count()));
  // 'R', then the port of its page when it serves one (one write, so one read takes it whole).
  char said[32] = {};
  const ssize_t n = r == 1 ? ::read(ready[0], said, sizeof said - 1) : -1;
  const bool served = n >= 1 && said[0] == 'R';
  ::close(ready[0]);
  if (served) {
    children_[part].web_port = std::atoi(said + 1);
    spdlog::info("{} serves on {} (pid {})", name(part), args.size() > 2 ? args[2] : "?", pid);
    return;
  }
  int status = 0;
  if (r == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    children_[part].done = true;
    throw CliError(kExitFailure, fmt::format("--processes: {} did not start serving within {} s", name(part), kStartTimeout.count()));
  }
  ::waitpid(pid, &status, 0);
  children_[part].done = true;
  throw CliError(WIFEXITED(status) && WEXITSTATUS(status) != 0 ? WEXITSTATUS(status) : kExitFailure,
                 fmt::format("--processes: {} did not start: {} (its message is above)", name(part), how_it_ended(status)));
}

void PartProcesses::watch() {
  std::unique_ptr<link::NetnsScope> here;  // to take a veth end down where it is
  try {
    here = inside(netns_);
  } catch (const CliError& e) {
    spdlog::warn("{}", e.what());
  }
  for (;;) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      return;  // ECHILD: none left
    }
    for (std::size_t k = 1; k < parts_.size(); ++k) {
      Child& c = children_[k];
      if (c.pid != pid) continue;
      c.how = how_it_ended(status);
      c.done.store(true);
      if (stopping_.load()) break;
      spdlog::error("{} ended: {}; the line now ends before it", name(k), c.how);
      try {
        link::net::set_interface_down(veths_[k - 1]->slave_end());
      } catch (const link::LinkError& e) {
        spdlog::warn("{}: {}", name(k), e.what());
      }
    }
  }
}

void PartProcesses::stop_children() {
  for (std::size_t k = 1; k < parts_.size(); ++k)
    if (children_[k].pid > 0 && !children_[k].done.load()) ::kill(children_[k].pid, SIGTERM);
  const auto all_done = [&] {
    for (std::size_t k = 1; k < parts_.size(); ++k)
      if (children_[k].pid > 0 && !children_[k].done.load()) return false;
    return true;
  };
  const bool watched = watcher_.joinable();
  const auto give_up = std::chrono::steady_clock::now() + kStopGrace;
  while (!all_done() && std::chrono::steady_clock::now() < give_up) {
    if (!watched) {  // before the watcher started: reap here
      for (std::size_t k = 1; k < parts_.size(); ++k) {
        Child& c = children_[k];
        if (c.pid > 0 && !c.done.load() && ::waitpid(c.pid, nullptr, WNOHANG) == c.pid) c.done.store(true);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (std::size_t k = 1; k < parts_.size(); ++k) {
    Child& c = children_[k];
    if (c.pid > 0 && !c.done.load()) {
      ::kill(c.pid, SIGKILL);
      if (!watched) ::waitpid(c.pid, nullptr, 0), c.done.store(true);
    }
  }
}

std::vector<std::string> PartProcesses::ended_early() {
  std::vector<std::string> out;
  if (stopping_.load()) return out;
  for (std::size_t k = 1; k < parts_.size(); ++k)
    if (children_[k].done.load()) out.push_back(fmt::format("{} ended: {}", name(k), children_[k].how));
  return out;
}

}  // namespace vdrive::cli
