#pragma once
// LineTap: something served together with the line in a real-time scenario run, such as DDS
// telemetry (`vdrive scenario run --veth --telemetry`). It sees every frame through the link it
// wraps and does its own work in a LoopService polled on the serving thread, exactly as around
// `vdrive run`'s event loop. The scenario library only knows this interface, so it does not
// depend on what taps it.
#include <functional>
#include <memory>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/runtime/loop_service.hpp"

namespace vdrive::network { class Network; }

namespace vdrive::scenario {

class LineTap {
public:
  virtual ~LineTap() = default;
  // The link the line is served through: wraps the `served` link given to the factory.
  virtual link::Link& link() = 0;
  virtual runtime::LoopService& service() = 0;
};

// Called once the real-time line is built; the tap lives until the run ends.
using LineTapFactory = std::function<std::unique_ptr<LineTap>(network::Network&, link::Link& served, const Clock&,
                                                              const runtime::LoopCounters&)>;

}  // namespace vdrive::scenario
