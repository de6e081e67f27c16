#pragma once
// The frames a master sends every bus cycle, for a process image of any length:
//   frame 0   LRW of piece 0, FRMW 0x0910 at the DC reference clock (only with DC),
//             BRD 0x0130 AL status (ORed over all slaves), BWR 0x0120 AL control (when asked);
//   frame k   LRW of piece k,
// the pieces cut from the image by split_process_image (lrw_split.hpp), one LRW per frame. All of a
// cycle's frames go out back to back and their replies are taken in any order
// (Transport::exchange with a span of frames). Every datagram of a cycle gets its own index, so a
// reply is matched to exactly one frame and a late reply to an earlier cycle is never taken.
//
// The cyclic task (cyclic_task.hpp) and the turnaround benchmark (bench/turnaround) both build
// their cycles here. Frames are allocated in the constructor; building and checking allocate
// nothing.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "master/datagram.hpp"
#include "master/frame.hpp"
#include "master/lrw_split.hpp"

namespace vdrive::master {

class CycleFrames {
public:
  // The LRW data that fits frame 0 beside FRMW (8 bytes), BRD (2) and BWR (2), each datagram with
  // its 10-byte header and 2-byte working counter: 1,438 bytes. Every piece is held to it.
  static constexpr std::size_t kMaxLrwBytes = kMaxEtherCatPayload - 4 * (kDatagramHeaderSize + kWkcSize) - 8 - 2 - 2;
  // A cycle's frames are told apart by a 64-bit mask (Transport::exchange): 92 KB of image.
  static constexpr std::size_t kMaxFrames = 64;

  // `pieces` in image order (empty: no process data, frame 0 carries FRMW/BRD/BWR only);
  // `reference` 0: no FRMW; `slave_count`: the expected working counter of FRMW and BRD.
  // Throws std::invalid_argument when the pieces need more than kMaxFrames frames or one is
  // longer than kMaxLrwBytes.
  CycleFrames(const MacAddress& source, std::vector<LrwPiece> pieces, std::uint16_t reference, std::uint16_t slave_count);

  std::size_t count() const { return frames_.size(); }
  // Datagram indexes one cycle uses (build() takes them from `first_index` on).
  std::uint8_t indexes_per_cycle() const { return static_cast<std::uint8_t>(pieces_.size() + 3); }
  std::size_t image_bytes() const { return image_bytes_; }
  const std::vector<LrwPiece>& pieces() const { return pieces_; }

  // Rebuilds every frame with `image` (image_bytes() long) as the LRW data; `al_control` != 0
  // adds the BWR of AL control in frame 0.
  void build(std::span<const std::uint8_t> image, std::uint8_t first_index, std::uint16_t al_control = 0);
  // The frames, to send; after Transport::exchange the answered ones hold their replies.
  std::span<Frame> frames() { return frames_; }

  // Of an answered frame i: the working counter of its LRW (0 without process data), whether it
  // is the piece's expected one, and whether every counter in it is (FRMW and BRD: one per slave).
  std::uint16_t lrw_wkc(std::size_t i) const;
  bool lrw_ok(std::size_t i) const;
  bool counters_ok(std::size_t i) const;
  // Of an answered frame 0: the BRD's AL status and working counter.
  std::uint16_t al_status() const;
  std::uint16_t al_wkc() const;
  // Copies what the reply of frame i carries at image offsets >= `from` (the inputs) into `image`.
  void take_inputs(std::size_t i, std::span<std::uint8_t> image, std::uint32_t from) const;

private:
  std::vector<LrwPiece> pieces_;
  std::vector<Frame> frames_;
  std::array<std::uint8_t, 8> no_time_{};  // FRMW data: the reference slave's time replaces it
  std::size_t image_bytes_ = 0;
  std::uint16_t reference_;
  std::uint16_t slave_count_;
  int frmw_slot_ = -1, brd_slot_ = -1;
};

}  // namespace vdrive::master
