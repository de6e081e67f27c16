#pragma once
// The telemetry's DDS names and domain (docs/telemetry.md). Topic names follow ROS 2's mapping
// of a topic /vdrive/X to the DDS topic rt/vdrive/X, so ROS 2 tools see /vdrive/axis_state etc.
#include <optional>
#include <stdexcept>

namespace vdrive::telemetry {

enum class Topic { axis_state, bus_state, events, control_request, control_reply };

inline constexpr const char* topic_name(Topic t) {
  switch (t) {
    case Topic::axis_state: return "rt/vdrive/axis_state";
    case Topic::bus_state: return "rt/vdrive/bus_state";
    case Topic::events: return "rt/vdrive/events";
    case Topic::control_request: return "rt/vdrive/control_request";
    case Topic::control_reply: return "rt/vdrive/control_reply";
  }
  return "";
}

// DDS domain ids vdrive accepts (ROS 2's usable range on Linux).
inline constexpr int kMaxDomain = 232;

class DomainError : public std::invalid_argument {
public:
  using std::invalid_argument::invalid_argument;
};

// DDS could not start: no participant, topic, reader or writer.
class DdsError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The option if given, else $ROS_DOMAIN_ID if set, else 0. Throws DomainError naming the source
// of a value that is not an integer in 0..kMaxDomain.
int resolve_domain(std::optional<int> option);

}  // namespace vdrive::telemetry
