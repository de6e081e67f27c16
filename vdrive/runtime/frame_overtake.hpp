#pragma once
// FrameOvertake: in real time, a frame that arrives while the event loop runs the line's firmware
// (a batch of control steps, every slave's interrupt handler after a frame) passes the ESCs and
// goes back between two slaves' firmware calls, instead of waiting for the whole line. On the
// silicon the ESC answers frames while the microcontroller works; with one thread for both, this
// is how a 64-drive line keeps a frame's turnaround near one drive's work. The firmware's reaction
// to such a frame (its interrupts) follows the batch it overtook.
//
// The link is asked only where that is cheap: after every firmware call when its peek is Free
// (receive ring, in-process queue); at most once per kSyscallPeekInterval when it is a system
// call; never when the link cannot tell (an impaired wire, a scenario's wire), where the loop
// works as it did: a frame waits for the batch. Virtual time (run_until) never overtakes, so
// scenarios stay deterministic. Loop thread only; no allocation, no locks.
#include <array>
#include <cstdint>
#include <span>

#include "common/clock.hpp"
#include "vdrive/link/link.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/loop_counters.hpp"

namespace vdrive::runtime {

// How often a link whose peek is a system call is asked while firmware runs.
constexpr Nanos kSyscallPeekInterval = 20'000;
// Frames taken in one go at most, so a flood cannot keep the firmware from running.
constexpr int kMaxFramesInOneGo = 16;

// One frame from the master through the ESCs and back to it, or on through the onward port
// (counted); the firmware's reaction is the caller's to run (Network::service_irqs). The frame
// goes out before the firmware reacts (architecture.md).
void pass_frame(network::Network& network, link::Link& link, std::span<std::uint8_t> frame, Nanos now,
                LoopCounters& counters);

class FrameOvertake final : public network::BetweenSlaves {
public:
  // `now`: the clock at the start of this loop round; a system-call peek is first made
  // kSyscallPeekInterval after it.
  FrameOvertake(network::Network& network, link::Link& link, const Clock& clock, LoopCounters& counters,
                Nanos now);

  // For Network::tick and service_irqs: this, or nullptr when the link cannot tell.
  network::BetweenSlaves* hook() { return cost_ == link::PeekCost::Unsupported ? nullptr : this; }
  // Takes the frames waiting now (if it is time to ask) and passes each.
  void run() override;

  // The frame buffer receive() fills for this round.
  std::span<std::uint8_t> buffer() { return buf_; }
  // A frame received for this round: passes it, then any frames already waiting behind it (the
  // rest of a cycle split over several frames), then services the firmware's interrupts, letting
  // frames overtake that.
  void serve_frame(std::size_t length, Nanos now);
  // Services the interrupts of frames that overtook, without overtaking again (so the loop moves
  // on to its timers even under a flood).
  void service_owed_irqs();

private:
  void take_waiting();

  network::Network& network_;
  link::Link& link_;
  const Clock& clock_;
  LoopCounters& counters_;
  link::PeekCost cost_;
  Nanos next_peek_;
  bool irqs_owed_ = false;
  std::array<std::uint8_t, link::kMaxFrame> buf_;
};

}  // namespace vdrive::runtime
