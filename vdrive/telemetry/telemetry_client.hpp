#pragma once
// TelemetryClient: the `vdrive telemetry` side of DDS: subscribes to the axis, bus and event
// topics of every vdrive in a domain, and sends control requests and waits for their replies.
// Works from any process on any machine in the same DDS domain (docs/telemetry.md).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "common/clock.hpp"
#include "vdrive/control/control_request.hpp"
#include "vdrive/telemetry/samples.hpp"

namespace vdrive::telemetry {

struct Event {
  Nanos time = 0;
  std::uint16_t slave = 0;
  std::string kind, text;
  std::uint32_t value = 0, previous = 0;
};

struct TelemetryHandlers {
  std::function<void(const AxisSample&)> axis;
  std::function<void(const BusSample&)> bus;
  std::function<void(const Event&)> event;
};

class TelemetryClient {
public:
  explicit TelemetryClient(int domain);  // throws DdsError
  ~TelemetryClient();
  TelemetryClient(const TelemetryClient&) = delete;
  TelemetryClient& operator=(const TelemetryClient&) = delete;

  // Takes what has arrived, waiting up to `wait` for something; calls the handlers (null ones:
  // that topic is not read). Returns how many samples were handled.
  std::size_t poll(Nanos wait, const TelemetryHandlers& handlers);

  // Sends one control request line (telemetry_request.hpp) once a vdrive listens, and waits for
  // its reply; nullopt if no vdrive answered within `timeout`. Throws control::ProtocolError for
  // a garbled reply.
  std::optional<control::ControlReply> call(const std::string& request_line, Nanos timeout);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdrive::telemetry
