#pragma once
// LineTelemetry: everything `vdrive run --telemetry` adds around its event loop, in one object:
// a TimedLink around the served link (turnaround), the Sampler on the loop thread, polled with
// the fault control's service, and the TelemetryPublisher's thread. Serve the line through
// link() and service() for as long as this lives.
#include <functional>
#include <memory>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/runtime/loop_service.hpp"
#include "vdrive/telemetry/telemetry_publisher.hpp"

namespace vdrive::network { class Network; }
namespace vdrive::runtime { struct LoopCounters; }
namespace vdrive::control { class FaultService; }

namespace vdrive::telemetry {

struct LineTelemetryOptions {
  double rate_hz = 100.0;
  int domain = 0;
  LinePlace place;            // a part of `vdrive run --processes N` (Sampler::set_place)
  PublisherOptions requests;  // who takes the control topic's requests (TelemetryPublisher)
};

class LineTelemetry {
public:
  // `faults` (may be null) carries out the control topic's fault requests and is polled with
  // the sampler. Throws std::invalid_argument for a bad rate, DdsError if DDS cannot start.
  LineTelemetry(network::Network& network, link::Link& served, const Clock& clock, const runtime::LoopCounters& counters,
                control::FaultService* faults, const LineTelemetryOptions& options, std::function<void()> wake);
  ~LineTelemetry();

  link::Link& link();
  runtime::LoopService& service();
  std::uint64_t published() const;
  std::uint64_t dropped() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdrive::telemetry
