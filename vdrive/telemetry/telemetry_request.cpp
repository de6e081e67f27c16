// Parsing of the telemetry control topic's requests. See telemetry_request.hpp.
#include "vdrive/telemetry/telemetry_request.hpp"

#include <fmt/core.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "ethercat/slave_ref.hpp"
#include "vdrive/control/control_protocol.hpp"

namespace vdrive::telemetry {
namespace {

using control::ProtocolError;

// "slave": a position (an integer from 1) or a station address ("0x1002").
void read_slave(const nlohmann::json& s, PlantSet& p) {
  if (s.is_string() && ecat::is_address_text(s.get<std::string>())) {
    try {
      p.station = ecat::parse_slave_ref(s.get<std::string>()).value;
    } catch (const std::invalid_argument& e) {
      throw ProtocolError(fmt::format("plant_set: 'slave': {}", e.what()));
    }
    return;
  }
  if (!s.is_number_integer() || s.get<std::int64_t>() < 1 || s.get<std::int64_t>() > std::numeric_limits<std::uint16_t>::max())
    throw ProtocolError(fmt::format("plant_set: 'slave' must be {}, not {}", ecat::kSlaveRefForms, s.dump()));
  p.slave = s.get<int>();
}

PlantSet read_plant_set(const nlohmann::json& j) {
  PlantSet p;
  for (const auto& [key, value] : j.items()) {
    if (key != "op" && key != "slave" && key != "external_load")
      throw ProtocolError(fmt::format("plant_set: unexpected field '{}' (plant_set takes slave, external_load)", key));
  }
  if (!j.contains("slave")) throw ProtocolError("plant_set: 'slave' is missing (the drive whose plant changes, from 1, or its station address)");
  read_slave(j["slave"], p);
  if (!j.contains("external_load")) throw ProtocolError("plant_set: 'external_load' is missing (N or N m on the load)");
  const nlohmann::json& f = j["external_load"];
  if (!f.is_number() || !std::isfinite(f.get<double>()))
    throw ProtocolError(fmt::format("plant_set: 'external_load' must be a finite number, not {}", f.dump()));
  p.external_load = f.get<double>();
  return p;
}

}  // namespace

TelemetryRequest parse_telemetry_request(std::string_view line) {
  nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw ProtocolError("request is not a JSON object");
  TelemetryRequest r;
  if (j.contains("op") && j["op"] == "plant_set") {
    r.kind = TelemetryRequest::Kind::plant_set;
    r.plant = read_plant_set(j);
  } else {
    r.kind = TelemetryRequest::Kind::fault;
    r.fault = control::parse_request(line);
  }
  return r;
}

}  // namespace vdrive::telemetry
