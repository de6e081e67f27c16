#pragma once
// TelemetryPublisher: the telemetry's half off the event loop. Its own thread drains the
// Sampler's queue and writes each sample to DDS (Fast DDS's write() allocates and locks, which
// the loop must not), and takes requests from the control topic, hands them to the Sampler to be
// carried out on the loop thread, and writes the replies to the reply topic.
#include <atomic>
#include <functional>
#include <memory>
#include <thread>

#include "vdrive/telemetry/sampler.hpp"

namespace vdrive::telemetry {

class TelemetryPublisher {
public:
  // Joins `domain` (throws DdsError) and starts the thread. `wake` (optional) cuts the event
  // loop's wait short after a request is queued (runtime::LoopWaker), as the control socket does.
  TelemetryPublisher(Sampler& sampler, int domain, std::function<void()> wake = {});
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
