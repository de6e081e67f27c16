#pragma once
// The master's cyclic task: every cycle one frame with
//   LRW   over the whole process image (outputs out, inputs back),
//   FRMW  0x0910 from the DC reference clock (drift compensation; only with DC),
//   BRD   0x0130 AL status (ORed over all slaves: equal to a state only when all are in it),
//   BWR   0x0120 AL control, only in the cycles after request_state(),
// sent at absolute deadlines start + k * cycle. The LRW working counter is compared with the
// expected one (sum over the slaves); a lost frame counts as a wrong working counter too.
//
// The image and the frame are allocated in the constructor; run_cycle() allocates nothing. The
// callbacks are called in the cycle: `outputs` before sending (write the image's outputs),
// `inputs` after the reply (read the image's inputs).
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/clock.hpp"
#include "master/al_state.hpp"
#include "master/frame.hpp"
#include "master/process_data.hpp"
#include "master/transport.hpp"

namespace vdrive::master {

struct CyclicStats {
  std::uint64_t cycles = 0;
  std::uint64_t wrong_wkc = 0;        // LRW working counter != expected (or no reply)
  std::uint64_t lost_frames = 0;      // no reply within the cycle
  std::uint16_t last_wkc = 0;
  std::uint16_t al_status = 0;        // last BRD 0x0130 (ORed)
  std::uint16_t al_wkc = 0;           // slaves that answered the BRD
  Nanos max_late = 0;                 // worst start of a cycle after its deadline
};

class CyclicTask {
public:
  using Callback = std::function<void(std::span<std::uint8_t> image)>;

  // `reference_station` 0: no DC FRMW in the frame. `slave_count` is the BRD's expected WKC.
  CyclicTask(Transport& transport, const ProcessImageLayout& layout, std::size_t slave_count, Nanos cycle,
             std::uint16_t reference_station = 0);

  // How long a cycle waits for its frame (default: the cycle time, at least 1 ms).
  void set_reply_timeout(Nanos timeout) { reply_timeout_ = timeout; }

  void on_outputs(Callback cb) { outputs_ = std::move(cb); }
  void on_inputs(Callback cb) { inputs_ = std::move(cb); }

  // The process image: outputs at [0, layout.output_bytes), inputs after them.
  std::span<std::uint8_t> image() { return image_; }

  // Writes AL control = state in the following cycles (BWR), until every slave reports it.
  void request_state(AlState state) { requested_ = static_cast<std::uint16_t>(state); }
  bool all_in(AlState state) const {
    return stats_.al_wkc == slave_count_ && stats_.al_status == static_cast<std::uint16_t>(state);
  }

  // One cycle now (no waiting). Returns true when the LRW working counter was as expected.
  bool run_cycle();
  // `cycles` cycles at the cycle time, from the next deadline on. Stops early when `until`
  // returns true (checked after each cycle). Returns the number of cycles run.
  std::uint64_t run(std::uint64_t cycles, const std::function<bool()>& until = {});

  const CyclicStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }
  Nanos cycle() const { return cycle_; }
  std::uint16_t expected_wkc() const { return layout_.expected_wkc; }

private:
  Transport& transport_;
  ProcessImageLayout layout_;
  std::uint16_t slave_count_;
  Nanos cycle_;
  Nanos reply_timeout_;
  std::uint16_t reference_;
  std::vector<std::uint8_t> image_;
  Frame frame_;
  Callback outputs_, inputs_;
  std::uint16_t requested_ = 0;
  Nanos next_ = 0;
  CyclicStats stats_;
};

}  // namespace vdrive::master
