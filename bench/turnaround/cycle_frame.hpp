#pragma once
// The frames a master sends every cycle, as the benchmark measures them:
//   LRW  over the process image (every drive's outputs and inputs),
//   FRMW 0x0910 at the DC reference clock (distributes the system time to the others),
//   BRD  0x0130 (AL status of every slave, ORed).
// An image too long for one frame is cut into equal pieces, one LRW per frame, as a master does
// with a long line; FRMW and BRD ride in the first frame. Rebuilt every cycle with fresh datagram
// indexes, so a late reply to an earlier cycle is never taken for this cycle's. Fixed-size
// storage: building and checking allocate nothing.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "master/frame.hpp"

namespace vdrive::bench {

// One slave's FMMU ranges in the logical image (for the expected LRW working counters).
struct SlaveImage {
  std::uint32_t output_logical = 0, output_bytes = 0;
  std::uint32_t input_logical = 0, input_bytes = 0;
};

class CycleFrames {
public:
  static constexpr std::size_t kMaxImagePerFrame = 1400;  // an LRW that fits a frame with FRMW + BRD
  static constexpr std::size_t kMaxFrames = 8;

  // `image_bytes` from logical `logical_start`; FRMW at station `reference`. `slaves` gives the
  // expected working counters (ETG: LRW +2 per slave whose outputs the piece covers, +1 per slave
  // whose inputs it covers; FRMW and BRD one per slave); empty: every counter must stay 0 (echo).
  CycleFrames(std::uint32_t logical_start, std::size_t image_bytes, std::uint16_t reference,
              const std::vector<SlaveImage>& slaves);

  std::size_t count() const { return count_; }
  // Rebuilds frame `i` of cycle `n` and returns its bytes.
  std::span<const std::uint8_t> build(std::size_t i, std::uint64_t n);
  // Which of this cycle's frames `reply` answers (and takes it), or -1.
  int accept(std::span<const std::uint8_t> reply);
  // After accept() returned i: whether frame i's working counters are the expected ones.
  bool working_counters_ok(std::size_t i) const;

private:
  struct Piece {
    std::uint32_t logical = 0;
    std::uint16_t bytes = 0;
    std::uint16_t lrw_wkc = 0;
  };
  std::array<master::Frame, kMaxFrames> frames_;
  std::array<Piece, kMaxFrames> pieces_{};
  std::array<std::uint8_t, kMaxImagePerFrame> zeros_{};
  std::size_t count_ = 0;
  std::uint16_t reference_;
  std::uint16_t per_slave_wkc_;  // FRMW and BRD
};

}  // namespace vdrive::bench
