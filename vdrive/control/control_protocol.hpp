#pragma once
// The runtime control protocol: one JSON object per line each way (docs/cli.md "Runtime
// control"). Requests:
//   {"op":"inject","fault":{"kind":"drop","probability":0.5,"duration":"100ms"}}
//   {"op":"clear","id":3}   {"op":"clear_all"}   {"op":"list"}
//   {"op":"signal_get","signal":"door"}   {"op":"signal_set","signal":"x.home","value":1}
//   {"op":"signals"}
//   {"op":"find_station","station":"0x1003"}  -> {"ok":true,"slave":3,...}: which slave here has
//   that station address (part 1 of `vdrive run --processes` asks the other parts, part_router.hpp)
// The fault's fields are a scenario file's (kind, slave, port, duration, direction, probability,
// delay, count, abort_code, code, position, load_scale, force), times as there ("250ms").
// Replies: {"ok":true,...} or {"ok":false,"status":"bad_request|denied|failed","error":"..."}.
#include <stdexcept>
#include <string>
#include <string_view>

#include "vdrive/control/control_request.hpp"

namespace vdrive::control {

// A request that is not valid: the message names the field and what was wrong with it.
class ProtocolError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

ControlRequest parse_request(std::string_view line);
// One line, without the newline.
std::string format_reply(const ControlReply& reply);
// The client's side: a reply line back into a ControlReply (throws ProtocolError if garbled).
ControlReply parse_reply(std::string_view line);

}  // namespace vdrive::control
