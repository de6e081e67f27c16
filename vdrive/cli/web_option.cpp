#include "vdrive/cli/web_option.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

#include "vdrive/cli/cli_error.hpp"

namespace vdrive::cli {

CLI::Option* add_web_option(CLI::App* cmd, std::string& web) {
  return cmd->add_option("--web", web,
                         "Serve the live page and its JSON API on [ADDR:]PORT (default ADDR 127.0.0.1; another address "
                         "serves other machines and prints a token changes need); docs/web.md")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            try {
              (void)web::parse_web_address(v);
              return {};
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
          },
          "[ADDR:]PORT"));
}

std::unique_ptr<web::WebServer> start_web(const std::string& spec, network::Network& network, const Clock& clock,
                                          const runtime::LoopCounters& counters, control::FaultService* faults,
                                          const std::string& source, const std::string& interface, std::function<void()> wake,
                                          bool best_effort, const web::WebServerOptions* base) {
  if (spec.empty()) return nullptr;
  web::WebServerOptions o;
  if (base != nullptr) o = *base;
  try {
    o.address = web::parse_web_address(spec);
  } catch (const std::invalid_argument& e) {
    throw CliError(kExitBadArguments, fmt::format("--web {}", e.what()));
  }
  return serve_web(std::move(o), network, clock, counters, faults, source, interface, std::move(wake), best_effort);
}

std::unique_ptr<web::WebServer> serve_web(web::WebServerOptions o, network::Network& network, const Clock& clock,
                                          const runtime::LoopCounters& counters, control::FaultService* faults,
                                          const std::string& source, const std::string& interface, std::function<void()> wake,
                                          bool best_effort) {
  o.source = source;
  o.interface = interface;
  o.version = VDRIVE_VERSION;
  std::unique_ptr<web::WebServer> server;
  try {
    server = std::make_unique<web::WebServer>(network, clock, counters, faults, o, std::move(wake));
  } catch (const web::WebError& e) {
    if (!best_effort) throw CliError(kExitFailure, e.what());
    spdlog::warn("no web page: {}", e.what());
    return nullptr;
  }
  // A later part's page: part 1's page reads it; its token stays out of the log.
  if (!o.token.empty())
    spdlog::info("web page on http://{}:{}/ (part 1's page reads it; changes need the run's token)", o.address.host, server->port());
  else
    spdlog::info("web page on {}", server->url());
  if (!o.address.loopback())
    spdlog::warn("the web page is served to other machines on {}: changes need the token in that address; "
                 "an SSH tunnel to 127.0.0.1 is the safer way (docs/web.md)", o.address.host);
  return server;
}

}  // namespace vdrive::cli
