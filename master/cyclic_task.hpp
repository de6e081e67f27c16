#pragma once
// The master's cyclic task: every cycle the frames of cycle_frames.hpp,
//   LRW   over the process image, in as many pieces and frames as it needs (outputs out, inputs
//         back; each piece a contiguous logical range cut on the slaves' FMMU windows),
//   FRMW  0x0910 from the DC reference clock (drift compensation; only with DC), in frame 0,
//   BRD   0x0130 AL status (ORed over all slaves: equal to a state only when all are in it), frame 0,
//   BWR   0x0120 AL control, only in the cycles after request_state(), frame 0,
// all sent back to back at absolute deadlines start + k * cycle, then the replies collected. Each
// piece's LRW working counter is compared with the one expected from the slaves whose windows it
// covers; a cycle with a wrong counter in any piece, or with any frame lost, counts as one wrong
// working counter.
//
// The image, the frames and the pieces are allocated in the constructor; run_cycle() allocates
// nothing. The callbacks are called in the cycle: `outputs` before sending (write the image's
// outputs), `inputs` after the replies (read the image's inputs; not called when a frame was lost).
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/clock.hpp"
#include "master/al_state.hpp"
#include "master/cycle_frames.hpp"
#include "master/process_data.hpp"
#include "master/transport.hpp"

namespace vdrive::master {

struct CyclicStats {
  std::uint64_t cycles = 0;
  std::uint64_t wrong_wkc = 0;        // cycles with an LRW working counter != expected or a frame lost
  std::uint64_t lost_frames = 0;      // frames with no reply within their cycle
  std::uint16_t last_wkc = 0;         // sum of the last cycle's LRW working counters
  std::uint16_t al_status = 0;        // last BRD 0x0130 (ORed)
  std::uint16_t al_wkc = 0;           // slaves that answered the BRD
  Nanos max_late = 0;                 // worst start of a cycle after its deadline
};

class CyclicTask {
public:
  using Callback = std::function<void(std::span<std::uint8_t> image)>;

  // `reference_station` 0: no DC FRMW in the frame. `slave_count` is the BRD's expected WKC. The
  // pieces' expected counters come from `layout.slaves`; a layout without them (made by hand) must
  // fit one LRW, which then expects `layout.expected_wkc`. Throws std::invalid_argument otherwise.
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

  // One cycle now (no waiting). Returns true when every frame came back with the LRW working
  // counters expected.
  bool run_cycle();
  // `cycles` cycles at the cycle time, from the next deadline on. Stops early when `until`
  // returns true (checked after each cycle). Returns the number of cycles run.
  std::uint64_t run(std::uint64_t cycles, const std::function<bool()>& until = {});

  const CyclicStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }
  Nanos cycle() const { return cycle_; }
  // Sum of the pieces' expected LRW counters (the layout's, unless a window had to be cut).
  std::uint16_t expected_wkc() const { return expected_wkc_; }
  // Frames per cycle, and the LRW pieces they carry.
  std::size_t frames_per_cycle() const { return frames_.count(); }
  const std::vector<LrwPiece>& pieces() const { return frames_.pieces(); }

private:
  Transport& transport_;
  std::uint32_t inputs_from_;      // image offset of the inputs (layout.output_bytes)
  std::uint16_t slave_count_;
  Nanos cycle_;
  Nanos reply_timeout_;
  std::vector<std::uint8_t> image_;
  CycleFrames frames_;
  std::uint64_t all_frames_;       // exchange()'s mask when every frame came back
  std::uint16_t expected_wkc_;
  Callback outputs_, inputs_;
  std::uint16_t requested_ = 0;
  Nanos next_ = 0;
  CyclicStats stats_;
};

}  // namespace vdrive::master
