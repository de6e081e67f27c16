#pragma once
// Distributed-clocks unit of one ESC: the register window 0x0900-0x09FF backed by a local clock.
// Local time = global clock time + a per-ESC start offset, running at a configurable drift;
// the system time (0x0910) is local time + offset (0x0920), corrected by the time-control loop
// (speed counter 0x0930, filters 0x0934/0x0935) when the master writes 0x0910.
// SYNC0/SYNC1 generation is programmed through 0x0980-0x09A8 and raised through tick().
#include <cstdint>
#include <span>

#include "common/clock.hpp"
#include "esc_model/frame_timing.hpp"

namespace vdrive::esc {

struct SyncEvents {
  bool sync0 = false;
  bool sync1 = false;
};

class DcUnit {
public:
  explicit DcUnit(const Clock& clock);

  void reset();

  // Register access; `offset` is relative to 0x0900, `in`/`out` stay within 0x0900-0x09FF.
  // `now` is global time (Clock::now()) at the moment of the access.
  void read(std::uint16_t offset, std::span<std::uint8_t> out, Nanos now);
  void write(std::uint16_t offset, std::span<const std::uint8_t> in, Nanos now, bool from_ecat);

  // A frame wrote 0x0900: latch the receive time of that frame at each port (local time).
  void latch_receive_times(const FrameTiming& timing);

  // Model parameters: ppm drift of this ESC's oscillator, and its local time at global time 0.
  void set_drift_ppm(double ppm);
  void set_start_offset(Nanos local_at_zero);

  // Local and system time at global time `now`.
  std::uint64_t local_time(Nanos now) const;
  std::uint64_t system_time(Nanos now) const;

  // Advance SYNC generation up to `now`; returns which SYNC signals fired since the last call.
  SyncEvents tick(Nanos now);
  // Global time of the next SYNC edge, or INT64_MAX if none is programmed.
  Nanos next_deadline() const;

private:
  const Clock& clock_;
  // State lives in the .cpp's private members below; kept explicit so tests can reason about it.
  std::uint8_t regs_[0x100] = {};
  double drift_ppm_ = 0.0;
  Nanos start_offset_ = 0;
  std::int64_t system_offset_ = 0;     // 0x0920
  std::int64_t control_correction_ = 0;  // accumulated by the time-control loop
  Nanos next_sync0_ = INT64_MAX;
  Nanos next_sync1_ = INT64_MAX;
};

}  // namespace vdrive::esc
