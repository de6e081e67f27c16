// Minimal placeholder; full DC unit follows.
#include "esc_model/dc_unit.hpp"

#include <algorithm>

namespace vdrive::esc {

DcUnit::DcUnit(const Clock& clock) : clock_(clock) { reset(); }

void DcUnit::reset() {
  std::fill(std::begin(regs_), std::end(regs_), 0);
  system_offset_ = 0;
  control_correction_ = 0;
  next_sync0_ = INT64_MAX;
  next_sync1_ = INT64_MAX;
}

void DcUnit::read(std::uint16_t offset, std::span<std::uint8_t> out, Nanos) {
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = (offset + i < 0x100) ? regs_[offset + i] : 0;
}

void DcUnit::write(std::uint16_t offset, std::span<const std::uint8_t> in, Nanos, bool) {
  for (std::size_t i = 0; i < in.size() && offset + i < 0x100; ++i) regs_[offset + i] = in[i];
}

void DcUnit::latch_receive_times(const FrameTiming&) {}
void DcUnit::set_drift_ppm(double ppm) { drift_ppm_ = ppm; }
void DcUnit::set_start_offset(Nanos t) { start_offset_ = t; }

std::uint64_t DcUnit::local_time(Nanos now) const {
  return static_cast<std::uint64_t>(start_offset_ + now);
}
std::uint64_t DcUnit::system_time(Nanos now) const {
  return local_time(now) + static_cast<std::uint64_t>(system_offset_ + control_correction_);
}

SyncEvents DcUnit::tick(Nanos) { return {}; }
Nanos DcUnit::next_deadline() const { return INT64_MAX; }

}  // namespace vdrive::esc
