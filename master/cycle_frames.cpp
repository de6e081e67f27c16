#include "master/cycle_frames.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "master/registers.hpp"
#include "master/transport.hpp"

namespace vdrive::master {

CycleFrames::CycleFrames(const MacAddress& source, std::vector<LrwPiece> pieces, std::uint16_t reference,
                         std::uint16_t slave_count)
    : pieces_(std::move(pieces)), reference_(reference), slave_count_(slave_count) {
  if (pieces_.size() > kMaxFrames) {
    throw std::invalid_argument("process image in " + std::to_string(pieces_.size()) + " pieces: more than " +
                                std::to_string(kMaxFrames) + " frames per cycle");
  }
  for (const LrwPiece& p : pieces_) {
    if (p.bytes > kMaxLrwBytes) throw std::invalid_argument("LRW piece of " + std::to_string(p.bytes) + " bytes does not fit a frame");
    image_bytes_ += p.bytes;
  }
  frames_.assign(std::max<std::size_t>(1, pieces_.size()), Frame(source));
  // Frame 0's slots are the same every cycle: [LRW] [FRMW] BRD [BWR].
  int slot = pieces_.empty() ? 0 : 1;
  if (reference_ != 0) frmw_slot_ = slot++;
  brd_slot_ = slot;
}

void CycleFrames::build(std::span<const std::uint8_t> image, std::uint8_t first_index, std::uint16_t al_control) {
  auto index = [&](std::size_t k) { return static_cast<std::uint8_t>(first_index + k); };
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    Frame& f = frames_[i];
    f.clear();
    if (i < pieces_.size()) {
      const LrwPiece& p = pieces_[i];
      f.add(Command::LRW, index(i), p.logical, image.subspan(p.offset, p.bytes));
    }
  }
  // FRMW, BRD and BWR follow the pieces' indexes, all in frame 0; kMaxLrwBytes leaves them room.
  Frame& first = frames_.front();
  const std::size_t n = pieces_.size();
  if (reference_ != 0) first.add(Command::FRMW, index(n), station_address(reference_, reg::kDcSystemTime), no_time_);
  first.add(Command::BRD, index(n + 1), station_address(0, reg::kAlStatus), std::uint16_t{2});
  if (al_control != 0) {
    const std::array<std::uint8_t, 2> control{static_cast<std::uint8_t>(al_control), static_cast<std::uint8_t>(al_control >> 8)};
    first.add(Command::BWR, index(n + 2), station_address(0, reg::kAlControl), control);
  }
}

std::uint16_t CycleFrames::lrw_wkc(std::size_t i) const { return i < pieces_.size() ? frames_[i].wkc(0) : 0; }

bool CycleFrames::lrw_ok(std::size_t i) const { return i >= pieces_.size() || frames_[i].wkc(0) == pieces_[i].expected_wkc; }

bool CycleFrames::counters_ok(std::size_t i) const {
  if (!lrw_ok(i)) return false;
  if (i != 0) return true;
  const Frame& f = frames_.front();
  if (frmw_slot_ >= 0 && f.wkc(static_cast<std::size_t>(frmw_slot_)) != slave_count_) return false;
  return f.wkc(static_cast<std::size_t>(brd_slot_)) == slave_count_;
}

std::uint16_t CycleFrames::al_status() const {
  const auto al = frames_.front().data(static_cast<std::size_t>(brd_slot_));
  return static_cast<std::uint16_t>(al[0] | (al[1] << 8));
}

std::uint16_t CycleFrames::al_wkc() const { return frames_.front().wkc(static_cast<std::size_t>(brd_slot_)); }

void CycleFrames::take_inputs(std::size_t i, std::span<std::uint8_t> image, std::uint32_t from) const {
  if (i >= pieces_.size()) return;
  const LrwPiece& p = pieces_[i];
  const std::uint32_t end = p.offset + p.bytes;
  if (end <= from) return;
  const std::uint32_t start = std::max(p.offset, from);
  const auto reply = frames_[i].data(0);
  std::copy(reply.begin() + (start - p.offset), reply.end(), image.begin() + start);
}

}  // namespace vdrive::master
