#pragma once
// The frame a master sends every cycle, as the benchmark measures it: one EtherCAT frame with
//   LRW  over the whole process image (every drive's outputs and inputs),
//   FRMW 0x0910 at the DC reference clock (distributes the system time to the others),
//   BRD  0x0130 (AL status of every slave, ORed).
// Built anew every cycle with fresh datagram indexes, so a late reply to an earlier cycle is never
// taken for this cycle's. Fixed-size storage: building and checking allocate nothing.
#include <array>
#include <cstdint>
#include <span>

#include "master/frame.hpp"

namespace vdrive::bench {

struct CycleExpectation {
  std::uint16_t lrw_wkc = 0;    // ETG: +2 per slave with outputs, +1 per slave with inputs
  std::uint16_t frmw_wkc = 0;   // the reference reads (+1), every other slave writes (+1)
  std::uint16_t brd_wkc = 0;    // one per slave
};

class CycleFrame {
public:
  static constexpr std::size_t kMaxImage = 1400;  // an LRW that fits one frame with the others

  // `image_bytes` of process data from logical address `logical_start`; FRMW at `reference`.
  CycleFrame(std::uint32_t logical_start, std::size_t image_bytes, std::uint16_t reference);

  // Rebuilds the frame for cycle `n` (indexes derived from n) and returns its bytes.
  std::span<const std::uint8_t> build(std::uint64_t n);
  // True when `reply` is this cycle's frame come back (layout and indexes match).
  bool accept(std::span<const std::uint8_t> reply) { return frame_.accept_reply(reply); }
  // After accept(): whether every working counter is the expected one.
  bool working_counters_are(const CycleExpectation& e) const;

private:
  master::Frame frame_;
  std::array<std::uint8_t, kMaxImage> image_{};
  std::uint32_t logical_start_;
  std::size_t image_bytes_;
  std::uint16_t reference_;
};

}  // namespace vdrive::bench
