#include "bench/turnaround/cycle_frame.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "master/transport.hpp"

namespace vdrive::bench {
namespace {

bool overlaps(std::uint32_t a, std::uint32_t a_len, std::uint32_t b, std::uint32_t b_len) {
  return a_len != 0 && b_len != 0 && a < b + b_len && b < a + a_len;
}

}  // namespace

using master::Command;

CycleFrames::CycleFrames(std::uint32_t logical_start, std::size_t image_bytes, std::uint16_t reference,
                         const std::vector<SlaveImage>& slaves)
    : reference_(reference), per_slave_wkc_(static_cast<std::uint16_t>(slaves.size())) {
  if (image_bytes == 0) throw std::invalid_argument("empty process image");
  count_ = (image_bytes + kMaxImagePerFrame - 1) / kMaxImagePerFrame;
  if (count_ > kMaxFrames) {
    throw std::invalid_argument("process image of " + std::to_string(image_bytes) + " bytes needs more than " +
                                std::to_string(kMaxFrames) + " frames");
  }
  const std::size_t piece = (image_bytes + count_ - 1) / count_;
  for (std::size_t i = 0; i < count_; ++i) {
    Piece& p = pieces_[i];
    p.logical = logical_start + static_cast<std::uint32_t>(i * piece);
    p.bytes = static_cast<std::uint16_t>(std::min(piece, image_bytes - i * piece));
    for (const SlaveImage& s : slaves) {
      if (overlaps(p.logical, p.bytes, s.output_logical, s.output_bytes)) p.lrw_wkc += 2;
      if (overlaps(p.logical, p.bytes, s.input_logical, s.input_bytes)) p.lrw_wkc += 1;
    }
  }
}

std::span<const std::uint8_t> CycleFrames::build(std::size_t i, std::uint64_t n) {
  master::Frame& f = frames_[i];
  const auto base = static_cast<std::uint8_t>(n * (kMaxFrames + 2) + i);
  f.clear();
  f.add(Command::LRW, base, pieces_[i].logical, std::span<const std::uint8_t>(zeros_.data(), pieces_[i].bytes));
  if (i == 0) {
    const std::uint8_t no_time[8] = {};
    f.add(Command::FRMW, static_cast<std::uint8_t>(base + kMaxFrames), master::station_address(reference_, 0x0910),
          std::span<const std::uint8_t>(no_time));
    f.add(Command::BRD, static_cast<std::uint8_t>(base + kMaxFrames + 1), 0x0130u << 16, std::uint16_t{2});
  }
  return f.bytes();
}

int CycleFrames::accept(std::span<const std::uint8_t> reply) {
  for (std::size_t i = 0; i < count_; ++i)
    if (frames_[i].accept_reply(reply)) return static_cast<int>(i);
  return -1;
}

bool CycleFrames::working_counters_ok(std::size_t i) const {
  const master::Frame& f = frames_[i];
  if (f.wkc(0) != pieces_[i].lrw_wkc) return false;
  return i != 0 || (f.wkc(1) == per_slave_wkc_ && f.wkc(2) == per_slave_wkc_);
}

}  // namespace vdrive::bench
