#pragma once
// Sampler: the telemetry's half on the event loop thread (a LoopService). At the configured rate
// it copies each slave's values (AL state from its ESC; 6041h, 6040h, 6061h, 6064h, 606Ch, 6077h,
// 60F4h, 603Fh and the plant's temperatures for a drive) and the line's counters into a
// preallocated SPSC queue, and notes events by comparing with the previous sample: AL state
// changes, 603Fh raised or cleared (" after a host stall of 12.3 ms" when one came just before),
// host stalls (runtime/host_stalls.hpp), faults started or ended (of the FaultInjector it watches,
// whoever injected them), named signals (network/signal_point.hpp) changed. A full queue drops the sample and counts it; nothing blocks, nothing
// allocates. Changes that come and go within one period are not seen.
//
// It also carries out the control topic's requests on the loop thread: they arrive through a
// second queue (request()), fault requests go to the fault handler (FaultService::handle in
// vdrive run), plant changes to the slave's plant, and replies go back through a third queue.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/runtime/loop_service.hpp"
#include "vdrive/runtime/spsc_queue.hpp"
#include "vdrive/telemetry/samples.hpp"
#include "vdrive/telemetry/telemetry_request.hpp"
#include "vdrive/telemetry/turnaround.hpp"

namespace vdrive::network { class Network; }
namespace vdrive::runtime { struct LoopCounters; }
namespace vdrive::fault { class FaultInjector; }

namespace vdrive::telemetry {

// Highest rate: one sample per 125 us, the shortest drive cycle of the products.
constexpr double kMaxRateHz = 8000.0;

// This process's place in a line cut over processes (`vdrive run --processes N`,
// docs/scale-out.md): samples and events name slaves by whole-line position and faults by
// run-wide id (control/run_fault_id.hpp), so the parts' publishers make one line to a subscriber.
struct LinePlace {
  std::size_t slaves_before = 0;  // the slaves of the parts before this one
  std::size_t part = 0;           // 0-based: 0 is part 1
  std::size_t parts = 1;
  std::size_t slaves_after = 0;   // the slaves of the parts after this one (part 1 names them in refusals)
};

struct SamplerSources {
  const runtime::LoopCounters* counters = nullptr;  // line frame counters (0 if null)
  TurnaroundStats* turnaround = nullptr;            // from a TimedLink (0 if null)
  const fault::FaultInjector* faults = nullptr;     // fault events (none if null)
};

class Sampler final : public runtime::LoopService {
public:
  static constexpr std::size_t kQueueSize = 4096;
  using FaultHandler = std::function<control::ControlReply(const control::ControlRequest&, Nanos)>;

  // Throws std::invalid_argument unless 0 < rate_hz <= kMaxRateHz. The first sample is taken at
  // the first poll().
  Sampler(network::Network& network, double rate_hz, SamplerSources sources = {});
  ~Sampler() override;
  // Set before the loop starts; without one, fault requests are refused.
  void set_fault_handler(FaultHandler handler) { fault_handler_ = std::move(handler); }
  // Set before the loop starts; one process is a line of its own by default.
  void set_place(const LinePlace& place) { place_ = place; }

  // Loop thread.
  void poll(Nanos now) override;
  Nanos next_deadline() const override { return next_; }

  // The telemetry thread (the one consumer of samples and replies, producer of requests).
  std::optional<Sample> pop() { return samples_->try_pop(); }
  bool request(TelemetryRequest&& r) { return requests_.try_push(std::move(r)); }
  std::optional<TelemetryReply> reply() { return replies_.try_pop(); }

  // Any thread.
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  Nanos period() const { return period_; }

private:
  struct Drive {  // the objects of one drive, looked up once
    drive::ObjectRef<std::int64_t> statusword, controlword, mode, position, velocity, torque, following_error, error_code, target_position,
        digital_inputs, probe_status, probe_position1;
  };
  void sample(Nanos now);
  void sample_faults(Nanos now);
  void sample_signals(Nanos now);
  void sample_stalls();
  // " after a host stall of 12.3 ms" if one ended just before `now`, else "".
  class RecentStall {
  public:
    RecentStall(const runtime::LoopCounters* counters, Nanos now);
    const char* text() const { return text_.data(); }

  private:
    std::array<char, 48> text_{};
  };
  void push(const Sample& s);
  // Slave `index` (0-based, this process's) as the whole line numbers it (from 1).
  std::uint16_t line_slave(std::size_t index) const { return static_cast<std::uint16_t>(index + 1 + place_.slaves_before); }
  int run_id(int id) const;
  void event(Nanos now, std::uint16_t slave, EventKind kind, std::uint32_t value, std::uint32_t previous, const char* text);
  control::ControlReply handle(const TelemetryRequest& r, Nanos now);

  network::Network& network_;
  SamplerSources sources_;
  Nanos period_;
  Nanos next_ = 0;
  std::vector<std::optional<Drive>> drives_;  // per slave; empty for a slave without a drive
  std::vector<std::uint16_t> last_al_, last_error_;
  std::vector<int> last_faults_;  // ids, capacity reserved up front
  std::vector<std::string> signal_labels_;   // per named signal: "door (di 0x6010:1)"
  std::vector<std::int64_t> last_signals_;
  std::unique_ptr<runtime::SpscQueue<Sample, kQueueSize>> samples_;
  runtime::SpscQueue<TelemetryRequest, 8> requests_;
  runtime::SpscQueue<TelemetryReply, 8> replies_;
  std::atomic<std::uint64_t> dropped_{0};
  std::uint64_t stalls_seen_ = 0;  // host stalls already sent as events
  FaultHandler fault_handler_;
  LinePlace place_;
};

}  // namespace vdrive::telemetry
