#pragma once
// Runs a program (the built `vdrive` binary) as a child process with stdout/stderr captured, for
// command-line tests: run to completion, or start, wait for a line, signal, and reap.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <vector>

namespace vdrive::test {

struct ProcessResult {
  int exit_code = -1;     // -1 if killed by a signal or not reaped in time
  std::string out, err;
};

class ChildProcess {
public:
  // `drop_to_nobody`: setgid/setuid(65534) in the child before exec (privilege tests as root).
  ChildProcess(const std::string& program, const std::vector<std::string>& args,
               bool drop_to_nobody = false) {
    int out_pipe[2], err_pipe[2];
    if (::pipe2(out_pipe, O_CLOEXEC) != 0 || ::pipe2(err_pipe, O_CLOEXEC) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out_pipe[1], 1);
      ::dup2(err_pipe[1], 2);
      if (drop_to_nobody && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(120);
      std::vector<char*> argv;
      argv.push_back(const_cast<char*>(program.c_str()));
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(program.c_str(), argv.data());
      ::_exit(127);
    }
    ::close(out_pipe[1]);
    ::close(err_pipe[1]);
    out_fd_ = out_pipe[0];
    err_fd_ = err_pipe[0];
  }
  ~ChildProcess() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_fd_ >= 0) ::close(out_fd_);
    if (err_fd_ >= 0) ::close(err_fd_);
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  void signal(int sig) { ::kill(pid_, sig); }

  // Reads output until stderr contains `text` or `timeout` passes; true if found.
  bool wait_for_stderr(const std::string& text, std::chrono::milliseconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (result_.err.find(text) == std::string::npos) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      if (left.count() <= 0 || !pump(static_cast<int>(left.count()))) return false;
    }
    return true;
  }

  // Waits for the child to exit (SIGKILL after `timeout`) and returns everything it printed.
  ProcessResult finish(std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end && pump(50)) {
    }
    int status = 0;
    for (;;) {
      pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) break;
      if (std::chrono::steady_clock::now() >= end) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        reaped_ = true;
        return result_;  // exit_code stays -1
      }
      pump(20);
    }
    reaped_ = true;
    while (pump(0)) {
    }
    result_.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result_;
  }

private:
  // Reads what is available within `timeout_ms`; false once both pipes are at EOF.
  bool pump(int timeout_ms) {
    pollfd fds[2] = {{out_fd_, POLLIN, 0}, {err_fd_, POLLIN, 0}};
    if (out_fd_ < 0 && err_fd_ < 0) return false;
    if (::poll(fds, 2, timeout_ms) <= 0) return out_fd_ >= 0 || err_fd_ >= 0;
    read_into(fds[0], out_fd_, result_.out);
    read_into(fds[1], err_fd_, result_.err);
    return out_fd_ >= 0 || err_fd_ >= 0;
  }
  static void read_into(const pollfd& p, int& fd, std::string& sink) {
    if (fd < 0 || (p.revents & (POLLIN | POLLHUP | POLLERR)) == 0) return;
    char buf[4096];
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      sink.append(buf, static_cast<std::size_t>(n));
    } else {
      ::close(fd);
      fd = -1;
    }
  }

  pid_t pid_ = -1;
  int out_fd_ = -1, err_fd_ = -1;
  bool reaped_ = false;
  ProcessResult result_;
};

inline ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                                 bool drop_to_nobody = false) {
  ChildProcess child(program, args, drop_to_nobody);
  return child.finish();
}

}  // namespace vdrive::test
