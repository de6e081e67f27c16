#pragma once
// A process image cut into LRW pieces, for lines whose image does not fit one frame.
//
// The image (every slave's outputs, then every slave's inputs, from `logical_start`; see
// process_data.hpp) is cut into contiguous pieces of at most `max_bytes`, one LRW datagram each.
// Cuts fall on the edges of the slaves' FMMU windows, as SOEM's I/O segments do, so that each
// slave's outputs and each slave's inputs travel in one datagram: its SyncManager buffer is then
// written or read whole by one datagram. Only a single window longer than a piece is cut inside.
//
// Expected working counter of a piece (ETG.1000.4, LRW): +2 per slave whose output window the
// piece overlaps (written), +1 per slave whose input window it overlaps (read). With cuts on the
// window edges the pieces' counters add up to the whole image's (process_data.hpp).
//
// Used by the cyclic task (cycle_frames.hpp) and the turnaround benchmark, so both cut alike.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vdrive::master {

// One slave's FMMU windows in the logical image (FMMU0 outputs, FMMU1 inputs).
struct SlaveImage {
  std::uint32_t output_logical = 0, output_bytes = 0;
  std::uint32_t input_logical = 0, input_bytes = 0;
};

struct LrwPiece {
  std::uint32_t logical = 0;        // the datagram's logical address
  std::uint32_t offset = 0;         // of its first byte in the image (logical - logical_start)
  std::uint16_t bytes = 0;
  std::uint16_t expected_wkc = 0;
};

// The working counter an LRW over [logical, logical + bytes) comes back with from these slaves.
std::uint16_t lrw_expected_wkc(std::uint32_t logical, std::uint32_t bytes, std::span<const SlaveImage> slaves);

// Pieces covering [logical_start, logical_start + image_bytes) in order, each at most `max_bytes`
// (> 0) long; none for an empty image. Without slaves the cuts fall every `max_bytes` and every
// expected counter is 0 (a responder that only echoes).
std::vector<LrwPiece> split_process_image(std::uint32_t logical_start, std::uint32_t image_bytes,
                                          std::span<const SlaveImage> slaves, std::size_t max_bytes);

}  // namespace vdrive::master
