#pragma once
// What the scenario runner needs of the cable between its master and the line: a Link for the
// built-in master (replies come back through receive(), which keeps the line running meanwhile),
// a capture of the master's frames, and a way to let time pass with no master at all (an external
// master drives the line). VirtualWire: virtual time, in process. RealtimeWire: real time over a
// pair of interfaces (veth) or one interface an external master is cabled to.
#include "common/clock.hpp"
#include "vdrive/link/link.hpp"

namespace vdrive::scenario {

class PcapngWriter;

class ScenarioWire : public link::Link {
public:
  virtual void set_capture(PcapngWriter* capture) = 0;
  // Serves the line until `until` (frames, timers); frames for the built-in master are dropped.
  virtual void serve_until(Nanos until) = 0;
};

}  // namespace vdrive::scenario
