#pragma once
// TelemetryPublisher: the telemetry's half off the event loop. Its own thread drains the
// Sampler's queue and writes each sample to DDS (Fast DDS's write() allocates and locks, which
// the loop must not), and takes requests from the control topic, hands them to the Sampler to be
// carried out on the loop thread, and writes the replies to the reply topic.
//
// In a line cut over processes (`vdrive run --processes N`) every part publishes its own slaves'
// samples (Sampler::set_place) and only part 1 takes requests, so each request has one answer:
// its fault requests go to the run's router (control/part_router.hpp), which blocks, so on this
// thread and never on the loop; its plant changes reach part 1's slaves.
#include <atomic>
#include <functional>
#include <memory>
#include <string_view>
#include <thread>

#include "vdrive/control/control_request.hpp"
#include "vdrive/telemetry/sampler.hpp"

namespace vdrive::telemetry {

// A fault request (and the JSON line it came as) -> its reply, on the telemetry thread.
using FaultRoute = std::function<control::ControlReply(const control::ControlRequest&, std::string_view line)>;

struct PublisherOptions {
  bool take_requests = true;  // false: no reader on the request topic, so no reply from here
  FaultRoute route;           // set: fault requests go there, not to the loop's fault handler
};

class TelemetryPublisher {
public:
  // Joins `domain` (throws DdsError) and starts the thread. `wake` (optional) cuts the event
  // loop's wait short after a request is queued (runtime::LoopWaker), as the control socket does.
  TelemetryPublisher(Sampler& sampler, int domain, std::function<void()> wake = {}, PublisherOptions options = {});
  ~TelemetryPublisher();  // stops the thread, publishing what is still queued first
  TelemetryPublisher(const TelemetryPublisher&) = delete;
  TelemetryPublisher& operator=(const TelemetryPublisher&) = delete;

  std::uint64_t published() const { return published_.load(std::memory_order_relaxed); }

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::atomic<std::uint64_t> published_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace vdrive::telemetry
