// Telemetry around a served line. See line_telemetry.hpp.
#include "vdrive/telemetry/line_telemetry.hpp"

#include "vdrive/control/fault_service.hpp"
#include "vdrive/telemetry/loop_services.hpp"
#include "vdrive/telemetry/sampler.hpp"
#include "vdrive/telemetry/telemetry_publisher.hpp"
#include "vdrive/telemetry/timed_link.hpp"

namespace vdrive::telemetry {

struct LineTelemetry::Impl {
  Impl(network::Network& network, link::Link& served, const Clock& clock, const runtime::LoopCounters& counters,
       control::FaultService* faults, const LineTelemetryOptions& o, std::function<void()> wake)
      : timed(served, clock, turnaround),
        sampler(network, o.rate_hz, SamplerSources{&counters, &turnaround, faults ? &faults->injector() : nullptr}),
        services(faults, &sampler) {
    if (faults != nullptr)
      sampler.set_fault_handler([faults](const control::ControlRequest& r, Nanos now) { return faults->handle(r, now); });
    sampler.set_place(o.place);
    publisher = std::make_unique<TelemetryPublisher>(sampler, o.domain, std::move(wake), o.requests);
  }
  TurnaroundStats turnaround;
  TimedLink timed;
  Sampler sampler;
  LoopServices services;
  std::unique_ptr<TelemetryPublisher> publisher;
};

LineTelemetry::LineTelemetry(network::Network& network, link::Link& served, const Clock& clock, const runtime::LoopCounters& counters,
                             control::FaultService* faults, const LineTelemetryOptions& options, std::function<void()> wake)
    : impl_(std::make_unique<Impl>(network, served, clock, counters, faults, options, std::move(wake))) {}
LineTelemetry::~LineTelemetry() = default;

link::Link& LineTelemetry::link() { return impl_->timed; }
runtime::LoopService& LineTelemetry::service() { return impl_->services; }
std::uint64_t LineTelemetry::published() const { return impl_->publisher->published(); }
std::uint64_t LineTelemetry::dropped() const { return impl_->sampler.dropped(); }

}  // namespace vdrive::telemetry
