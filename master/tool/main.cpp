// vdrive-master: the project's EtherCAT master as a command-line tool.
//
//   vdrive-master scan --iface IF [--state init|preop|safeop|op] [--json]
//
// Prints one line (or one JSON object) per slave: position, configured address, identity, name
// and AL state. Exit status: 0 success, 1 link/line error or no slaves, 2 the requested state was not reached
// by every slave (the slaves are still printed, with their AL status codes), CLI11's own codes for
// a bad command line. Errors are one line on stderr.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "master/al_state.hpp"
#include "master/master.hpp"
#include "vdrive/link/raw_socket_link.hpp"

namespace {

using vdrive::master::AlState;
using vdrive::master::Slave;

std::string hex32(std::uint32_t v) { return fmt::format("0x{:08X}", v); }

nlohmann::json to_json(const Slave& s) {
  nlohmann::json j;
  j["position"] = s.position;
  j["station"] = fmt::format("0x{:04X}", s.station);
  j["vendor_id"] = hex32(s.info.vendor_id);
  j["product_code"] = hex32(s.info.product_code);
  j["revision"] = hex32(s.info.revision);
  j["serial"] = hex32(s.info.serial);
  j["name"] = s.info.name;
  j["order"] = s.info.order;
  j["group"] = s.info.group;
  j["mailbox"] = {{"rx_offset", s.info.mailbox_rx_offset}, {"rx_size", s.info.mailbox_rx_size},
                  {"tx_offset", s.info.mailbox_tx_offset}, {"tx_size", s.info.mailbox_tx_size},
                  {"protocols", fmt::format("0x{:04X}", s.info.mailbox_protocols)}};
  j["state"] = std::string(vdrive::master::to_string(s.state()));
  j["al_error"] = s.al.error;
  j["al_status_code"] = fmt::format("0x{:04X}", s.al.status_code);
  return j;
}

int run_scan(const std::string& iface, const std::optional<AlState>& target, bool json) {
  vdrive::link::RawSocketLink link(iface);
  vdrive::master::Master master(link);
  if (master.scan() == 0) {
    throw std::runtime_error("no EtherCAT slaves on " + iface + " (frames come back with working counter 0)");
  }
  // scan() and request_state() leave each slave's AL status as last read.
  const bool reached = target ? master.request_state(*target) : true;

  if (json) {
    nlohmann::json out;
    out["interface"] = iface;
    out["slaves"] = nlohmann::json::array();
    for (const Slave& s : master.slaves()) out["slaves"].push_back(to_json(s));
    if (target) {
      out["requested_state"] = std::string(vdrive::master::to_string(*target));
      out["state_reached"] = reached;
    }
    std::puts(out.dump(2).c_str());
  } else {
    for (const Slave& s : master.slaves()) std::puts(vdrive::master::describe(s).c_str());
  }
  if (!reached) {
    std::fprintf(stderr, "vdrive-master: not every slave reached %s\n",
                 std::string(vdrive::master::to_string(*target)).c_str());
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vdrive-master: a small EtherCAT master (scan a line, bring it to a state)"};
  app.require_subcommand(1);
  std::string iface;
  std::string state_text;
  bool json = false;
  CLI::App* scan = app.add_subcommand("scan", "Find the slaves on an interface and print their identities");
  scan->add_option("--iface,-i", iface, "Network interface the line is connected to")->required();
  scan->add_option("--state,-s", state_text, "Bring every slave to this state: init, preop, safeop, op")
      ->check(CLI::IsMember({"init", "preop", "safeop", "op"}, CLI::ignore_case));
  scan->add_flag("--json", json, "Print JSON instead of one line per slave");
  CLI11_PARSE(app, argc, argv);

  try {
    std::optional<AlState> target;
    if (!state_text.empty()) target = vdrive::master::parse_al_state(state_text);
    return run_scan(iface, target, json);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vdrive-master: %s\n", e.what());
    return 1;
  }
}
