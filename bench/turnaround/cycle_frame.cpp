#include "bench/turnaround/cycle_frame.hpp"

#include <stdexcept>
#include <string>

#include "master/transport.hpp"

namespace vdrive::bench {

using master::Command;

CycleFrame::CycleFrame(std::uint32_t logical_start, std::size_t image_bytes, std::uint16_t reference)
    : logical_start_(logical_start), image_bytes_(image_bytes), reference_(reference) {
  if (image_bytes_ > kMaxImage) {
    throw std::invalid_argument("process image of " + std::to_string(image_bytes_) + " bytes does not fit one frame (at most " +
                                std::to_string(kMaxImage) + ")");
  }
}

std::span<const std::uint8_t> CycleFrame::build(std::uint64_t n) {
  const auto base = static_cast<std::uint8_t>(n * 3);
  const std::uint8_t no_time[8] = {};
  frame_.clear();
  frame_.add(Command::LRW, base, logical_start_, std::span<const std::uint8_t>(image_.data(), image_bytes_));
  frame_.add(Command::FRMW, static_cast<std::uint8_t>(base + 1), master::station_address(reference_, 0x0910),
             std::span<const std::uint8_t>(no_time));
  frame_.add(Command::BRD, static_cast<std::uint8_t>(base + 2), 0x0130u << 16, std::uint16_t{2});
  return frame_.bytes();
}

bool CycleFrame::working_counters_are(const CycleExpectation& e) const {
  return frame_.wkc(0) == e.lrw_wkc && frame_.wkc(1) == e.frmw_wkc && frame_.wkc(2) == e.brd_wkc;
}

}  // namespace vdrive::bench
