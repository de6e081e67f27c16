#include "vdrive/cli/control_client.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/control/control_socket.hpp"

namespace vdrive::cli {
namespace {

constexpr Nanos kReplyTimeout = 5'000'000'000;

std::string path_of(const ControlTarget& t, const std::string& command) {
  if (!t.control.empty()) return t.control;
  if (t.iface.empty())
    throw CliError(kExitBadArguments,
                   fmt::format("{}: --iface IF (the interface vdrive run serves) or --control PATH is required", command));
  return control::default_control_path(t.iface);
}

}  // namespace

void add_control_target(CLI::App* cmd, ControlTarget& t) {
  cmd->add_option("--iface,-i", t.iface, "Interface (or TAP) the vdrive run to control serves");
  cmd->add_option("--control", t.control, "Control socket of that vdrive run, if it was given --control");
  cmd->add_flag("--json", t.json, "Print the server's JSON reply line");
}

control::ControlReply control_request(const ControlTarget& t, const nlohmann::json& req, const std::string& command) {
  const std::string path = path_of(t, command);
  std::string line;
  try {
    line = control::control_call(path, req.dump(), kReplyTimeout);
  } catch (const control::ControlSocketError& e) {
    const bool denied = e.kind() == control::ControlSocketError::Kind::not_permitted;
    throw CliError(denied ? kExitNotPermitted : kExitFailure,
                   e.kind() == control::ControlSocketError::Kind::no_server
                       ? fmt::format("no vdrive serves {}: {}", t.control.empty() ? t.iface : t.control, e.what())
                       : std::string(e.what()));
  }
  control::ControlReply reply;
  try {
    reply = control::parse_reply(line);
  } catch (const control::ProtocolError& e) {
    throw CliError(kExitFailure, e.what());
  }
  if (t.json) fmt::print("{}\n", line);
  switch (reply.status) {
    case control::ControlReply::Status::ok: return reply;
    case control::ControlReply::Status::bad_request: throw CliError(kExitBadArguments, reply.error);
    case control::ControlReply::Status::denied: throw CliError(kExitNotPermitted, reply.error);
    case control::ControlReply::Status::failed: break;
  }
  throw CliError(kExitFailure, reply.error);
}

}  // namespace vdrive::cli
