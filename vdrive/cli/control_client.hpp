#pragma once
// The client side of a running `vdrive run`'s control socket, shared by `vdrive fault` and
// `vdrive signal`: which socket (--iface or --control), one request and its reply, and the exit
// codes of docs/cli.md (the server refuses: 2; a peer it denies: 4; no server: 1).
#include <string>

#include <nlohmann/json.hpp>

#include "vdrive/control/control_request.hpp"

namespace CLI { class App; }

namespace vdrive::cli {

struct ControlTarget {
  std::string iface;
  std::string control;
  bool json = false;  // print the reply line as it came
};

void add_control_target(CLI::App* command, ControlTarget& target);

// Sends one request; returns the reply if it succeeded, else throws CliError with the reply's
// error. `command` names the caller in messages ("fault", "signal").
control::ControlReply control_request(const ControlTarget& target, const nlohmann::json& request,
                                      const std::string& command);

}  // namespace vdrive::cli
