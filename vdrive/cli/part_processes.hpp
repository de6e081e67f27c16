#pragma once
// The processes of a line spread over cores (`vdrive run --processes N`, docs/scale-out.md): the
// veth pairs that chain part k's onward port (--next-iface) to part k+1's master side (--iface),
// and parts 2..N as child processes running `vdrive run` on them, each pinned to its core. Part 1
// is the calling process's own to serve.
//
// A child is started with its parent's death signal set (it ends when the parent dies) and tells
// it over a pipe when it serves (with the port of its web page, when it has one), so the parent
// starts serving only when the whole line answers; a child that fails before that is an error
// naming the part and its exit code. A child that ends
// while the line runs takes its master-side end of the veth down, so the part before it loses
// link on its port 1 and closes the line there, as a line does when a slave loses power; the
// parent logs it and reports it at the end. The destructor stops the children (SIGTERM, then
// SIGKILL after kStopGrace) and removes the veth pairs. With a namespace the veth pairs are made in
// it and the children open their ends there (`--netns`); the children themselves start outside it.
#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "vdrive/network/line_parts.hpp"
#include "vdrive/cli/veth_pair.hpp"

namespace vdrive::cli {

constexpr std::chrono::seconds kStopGrace{5};
constexpr std::chrono::seconds kStartTimeout{30};

class PartProcesses {
public:
  // `veth_prefix`: names are PREFIX + k + "o"/"i" (part k's onward end, part k+1's master end).
  // `child_args(k, in, next)` gives part k's arguments after "vdrive" (k >= 1), `in` its master-side
  // interface, `next` the onward interface the previous part leads to (empty for the last part).
  // Throws CliError: the veth pairs cannot be made (not root), a child fails to start or to
  // serve within kStartTimeout.
  using ArgsOf = std::function<std::vector<std::string>(std::size_t part, const std::string& in, const std::string& next)>;
  // `netns` (may be empty): the veth pairs are made inside that namespace; `child_args` gives the
  // children --netns to open their interfaces there.
  PartProcesses(const std::vector<network::LinePart>& parts, const std::string& veth_prefix, const std::string& netns,
                const ArgsOf& child_args);
  ~PartProcesses();
  PartProcesses(const PartProcesses&) = delete;
  PartProcesses& operator=(const PartProcesses&) = delete;

  // Part 1's onward interface (the first pair's end), empty with one part.
  std::string first_onward() const { return veths_.empty() ? std::string{} : veths_.front()->master_end(); }
  // The loopback port of part `part`'s web page (0-based, >= 1) as it said when it started; 0:
  // it serves none.
  int web_port(std::size_t part) const { return children_[part].web_port; }
  // A sentence per part that ended while serving ("part 2 (slaves 3-4) ended: exit code 1"); empty
  // while all serve. Safe from any thread after the parts ended (the watcher has been joined).
  std::vector<std::string> ended_early();

private:
  struct Child {
    pid_t pid = -1;
    std::atomic<bool> done{false};
    std::string how;  // how it ended, set by the watcher
    int web_port = 0;
  };
  void start(std::size_t part, const std::vector<std::string>& args);
  void watch();
  void stop_children();
  std::string name(std::size_t part) const;

  std::vector<network::LinePart> parts_;
  std::string netns_;
  std::vector<std::unique_ptr<VethPair>> veths_;
  std::unique_ptr<Child[]> children_;  // by part; part 0 is the caller's own
  std::atomic<bool> stopping_{false};
  std::thread watcher_;
};

}  // namespace vdrive::cli
