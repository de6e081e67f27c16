#pragma once
// A request on the telemetry control topic (rt/vdrive/control_request): one JSON line, either a
// runtime control request as the control socket takes it (inject, clear, clear_all, list:
// control_protocol.hpp) or a plant change that socket does not have:
//   {"op":"plant_set","slave":1,"external_load":2.5}
// external_load is the external force/torque on the load (N or N m, the plant's load units),
// Plant::set_external_load; it stays until set again (0 removes it).
#include <cstdint>
#include <string_view>

#include "vdrive/control/control_request.hpp"

namespace vdrive::telemetry {

struct PlantSet {
  int slave = 0;              // from 1; 0 when named by its station address
  std::uint16_t station = 0;  // the station address it was named by ("0x1002"), else 0
  double external_load = 0.0;
};

struct TelemetryRequest {
  enum class Kind : std::uint8_t { fault, plant_set };
  Kind kind = Kind::fault;
  control::ControlRequest fault;  // Kind::fault
  PlantSet plant;                 // Kind::plant_set
  std::uint64_t ticket = 0;       // matches the reply to the request (the publisher's bookkeeping)
};

struct TelemetryReply {
  std::uint64_t ticket = 0;
  control::ControlReply reply;
};

// Throws control::ProtocolError naming the field and what was wrong.
TelemetryRequest parse_telemetry_request(std::string_view line);

}  // namespace vdrive::telemetry
