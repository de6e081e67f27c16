#pragma once
// FaultService: runtime control on the event loop's thread: faults (it owns the FaultInjector of
// a served network), signals (signal_requests.hpp) and which slave has a station address
// (find_station, for part 1 of `vdrive run --processes`: part_router.hpp). Other threads (the control socket's) hand it requests with call(), which the
// loop picks up in poll() through a lock-free SPSC queue and answers through another, waking
// the caller with an eventfd. poll() with nothing pending is one atomic load plus a deadline
// compare; faults with a duration end at their deadline (next_deadline() joins the loop's).
// Every change is logged at info level, whoever asked (socket, DDS, the page, a network file):
// injected, one-shot applied, cleared, and ended because its duration ran out.
// After every change the ImpairedLink (if any) re-reads the wire settings, so a clean wire
// costs the frame path one branch.
#include <cstdint>
#include <mutex>
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "vdrive/control/control_request.hpp"
#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/runtime/loop_service.hpp"
#include "vdrive/runtime/spsc_queue.hpp"

namespace vdrive::fault { class ImpairedLink; class WireImpairment; }

namespace vdrive::control {

class FaultService final : public runtime::LoopService {
public:
  // `wire` and `link` may be null (then wire faults other than link_down are refused).
  FaultService(network::Network& network, fault::WireImpairment* wire, fault::ImpairedLink* link);
  ~FaultService() override;
  FaultService(const FaultService&) = delete;
  FaultService& operator=(const FaultService&) = delete;

  // Loop thread.
  void poll(Nanos now) override;
  Nanos next_deadline() const override { return std::min(injector_.next_deadline(), next_armed()); }
  // Carries out one request now (poll() does this for each queued one).
  ControlReply handle(const ControlRequest& request, Nanos now);

  // Any thread but the loop's (the control socket's, the telemetry's): queues `request` for the
  // loop and waits up to `timeout` for its reply; a `failed` reply if the loop is busy or does not
  // answer in time. Callers take turns (the queues have one producer and one consumer each).
  ControlReply call(ControlRequest request, Nanos timeout);

  const fault::FaultInjector& injector() const { return injector_; }
  // See fault::FaultInjector::set_later_slaves.
  void set_later_slaves(std::size_t count) { injector_.set_later_slaves(count); }

  // Before the loop starts: a fault to inject when the loop's clock reaches `at` (a network
  // file's armed faults); the outcome is logged with `origin`, a refusal as a warning.
  void arm(const fault::FaultSpec& spec, Nanos at, std::string origin);
  bool has_armed() const { return !armed_.empty(); }
  // What call() does after queueing a request to cut the loop's wait short (runtime::LoopWaker).
  // Set before the loop and the control thread start.
  void set_wake(std::function<void()> wake) { wake_ = std::move(wake); }

private:
  struct Armed {
    fault::FaultSpec spec;
    Nanos at = 0;
    std::string origin;
  };
  void changed();
  void inject_armed(Nanos now);
  Nanos next_armed() const;

  network::Network& network_;
  fault::FaultInjector injector_;
  fault::ImpairedLink* link_;
  runtime::SpscQueue<ControlRequest, 4> requests_;
  runtime::SpscQueue<ControlReply, 4> replies_;
  int reply_event_ = -1;  // eventfd: the loop signals a reply
  std::function<void()> wake_;
  std::mutex callers_;             // call(): one caller at a time, never the loop
  std::uint64_t next_seq_ = 1;
  std::vector<Armed> armed_;      // sorted by `at`
  std::size_t armed_done_ = 0;    // armed_[0, armed_done_) injected
};

}  // namespace vdrive::control
