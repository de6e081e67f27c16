#pragma once
// `--web [ADDR:]PORT` on `vdrive run`, `vdrive demo` and `vdrive scenario run`: the live page and
// its JSON API (docs/web.md), started around a served line.
#include <functional>
#include <memory>
#include <string>

#include "common/clock.hpp"
#include "vdrive/web/web_server.hpp"

namespace CLI { class App; class Option; }
namespace vdrive::network { class Network; }
namespace vdrive::runtime { struct LoopCounters; }
namespace vdrive::control { class FaultService; }

namespace vdrive::cli {

// Adds --web to `cmd`, checked as [ADDR:]PORT when parsed.
CLI::Option* add_web_option(CLI::App* cmd, std::string& web);

// The web server for `spec` (nullptr when empty), its address logged (and a warning when other
// machines can reach it); CliError for an address it cannot listen on (exit 1) or a bad spec (2).
// `best_effort`: an address it cannot listen on is a warning and no page (the demo's default port).
// `base` (optional): the server's other options (a line over processes); its address, source, interface and
// version are set here.
std::unique_ptr<web::WebServer> start_web(const std::string& spec, network::Network& network, const Clock& clock,
                                          const runtime::LoopCounters& counters, control::FaultService* faults,
                                          const std::string& source, const std::string& interface, std::function<void()> wake,
                                          bool best_effort = false, const web::WebServerOptions* base = nullptr);

// The same for a server whose options are whole already, its address included (a later part's
// page of `run --processes`, on a loopback port of its own).
std::unique_ptr<web::WebServer> serve_web(web::WebServerOptions options, network::Network& network, const Clock& clock,
                                          const runtime::LoopCounters& counters, control::FaultService* faults,
                                          const std::string& source, const std::string& interface, std::function<void()> wake,
                                          bool best_effort = false);

}  // namespace vdrive::cli
