#pragma once
// Where a signal is read or written: an object entry of a slave (its value as the firmware stores
// it, e.g. a digital input terminal's channel) or a connection of a drive's plant (its limit and
// home switches, touch probe inputs, and the holding brake's coil). Written as text in network
// files, the control socket and scenarios: "di 0x6000:1" (slave, entry) or "x.home" (slave,
// connection); a slave by its name or its position from 1.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace vdrive::network {

// A plant connection is one bit: 1 = the switch or input is actuated, 1 = the brake released.
// Read, a switch gives what the plant's sensor reports (or'ed with what was written to it) and
// brake_release what the drive's brake output commands; written, a switch is actuated from outside
// (or'ed with the sensor) and brake_release drives the coil instead of the drive.
enum class PlantConnection : std::uint8_t { negative_limit, positive_limit, home, probe1, probe2, brake_release };

std::string_view connection_name(PlantConnection c);
std::optional<PlantConnection> connection_from_name(std::string_view name);
// "negative_limit, positive_limit, home, probe1, probe2, brake_release", for messages.
std::string connection_names();

struct SignalPoint {
  std::size_t slave = 0;                   // 0-based, in the order the network was given
  std::optional<PlantConnection> plant;    // set: this plant connection; else the entry
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  bool operator==(const SignalPoint&) const = default;
};

// "NAME INDEX:SUB" or "NAME.CONNECTION" (INDEX and SUB decimal or 0x hex; NAME one of
// `slave_names`, or a position from 1). Throws std::invalid_argument saying what is wrong.
SignalPoint parse_signal_point(std::string_view text, std::span<const std::string> slave_names);
// The point as parse_signal_point reads it ("di 0x6000:1", "x.home"); positions from 1 where
// `slave_names` has no name for the slave.
std::string format_signal_point(const SignalPoint& point, std::span<const std::string> slave_names);

// A name for a point, given in the network file (`signals:`), for the control socket, scenarios
// and telemetry.
struct NamedSignal {
  std::string name;
  SignalPoint point;
  std::string origin;   // where it was given, for messages ("bench.yaml:14"); may be empty
};

// `text` as a named signal's point, else as a point (parse_signal_point). Throws
// std::invalid_argument listing the names when it is neither.
SignalPoint named_or_parsed_point(std::string_view text, std::span<const NamedSignal> signals,
                                  std::span<const std::string> slave_names);

}  // namespace vdrive::network
