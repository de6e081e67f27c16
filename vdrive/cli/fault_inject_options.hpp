#pragma once
// The fault fields of an inject request as command-line options, shared by `vdrive fault inject`
// (control socket) and `vdrive telemetry inject` (DDS control topic): the same options, turned
// into the same JSON fault object that fault::read_fault checks on the serving side.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace CLI { class App; }

namespace vdrive::cli {

struct FaultInjectOptions {
  std::string kind;
  std::optional<std::string> slave;  // a position (1 = first) or a station address, "0x1002"
  std::optional<int> port, count;
  std::optional<std::string> duration, direction, delay, abort_code, code;
  std::optional<double> probability, position, load_scale, force;
};

// `kind` and every field option on `inject`.
void add_fault_inject_options(CLI::App* inject, FaultInjectOptions& o);

// {"kind": ..., and each field given}.
nlohmann::json fault_json(const FaultInjectOptions& o);

}  // namespace vdrive::cli
