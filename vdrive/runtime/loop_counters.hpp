#pragma once
// The event loop's frame counters: written by the loop thread only (bump), read by any thread
// (a status line, telemetry).
#include <atomic>
#include <cstdint>

#include "vdrive/runtime/host_stalls.hpp"

namespace vdrive::runtime {

struct LoopCounters {
  std::atomic<std::uint64_t> frames_in{0};    // EtherCAT frames received from the link
  std::atomic<std::uint64_t> frames_out{0};   // frames sent back to the master (returned ones too)
  std::atomic<std::uint64_t> dropped{0};      // frames the line destroyed (malformed, cable cut)
  std::atomic<std::uint64_t> send_failed{0};  // replies the link refused (link down, full)
  // With an onward port (OnwardLink): frames sent on beyond this process, frames that came back
  // (and went on to the master: frames_out counts them too), and the onward link's carrier.
  std::atomic<std::uint64_t> onward{0};
  std::atomic<std::uint64_t> returned{0};
  std::atomic<bool> onward_link{false};
  std::atomic<bool> has_onward{false};  // set once by OnwardLink
  // Times the loop ran late because the host did not run it (host_stalls.hpp), with what the
  // drives saw; written by serve_once, never in virtual time.
  HostStalls stalls;
};

// Only the loop thread writes, so a relaxed load+store suffices (and avoids a locked RMW).
inline void bump(std::atomic<std::uint64_t>& counter) {
  counter.store(counter.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}

}  // namespace vdrive::runtime
