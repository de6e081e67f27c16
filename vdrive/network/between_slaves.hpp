#pragma once
// BetweenSlaves: work that Network::tick and Network::service_irqs let run after each slave's
// firmware call, while they go through a line. The event loop uses it to let a frame that arrived
// meanwhile pass the ESCs at once (runtime::FrameOvertake), as on the silicon, where the ESC
// answers frames while the microcontroller works. It must not run firmware itself.
namespace vdrive::network {

class BetweenSlaves {
public:
  virtual void run() = 0;

protected:
  ~BetweenSlaves() = default;
};

}  // namespace vdrive::network
