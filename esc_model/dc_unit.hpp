#pragma once
// Distributed-clocks unit of one ESC (ET1100-class, 64-bit DC): the register window 0x0900-0x09FF
// backed by a free-running local oscillator.
//
// Time model (all in ns):
//   local(now)  = start_offset + now * (1 + drift_ppm * 1e-6)          (this ESC's oscillator)
//   system(now) = local(now) + offset (0x0920) + correction(now)       (the "local copy of system time")
// correction is the time-control loop's: every ECAT write of 0x0910 compares the local copy at the
// frame's SOF with written value + system time delay (0x0928); the difference (0x092C, bit31 =
// local copy smaller) is removed by slewing (the ET1100 adds 9 or 11 instead of 10 ns per 10 ns
// clock; modelled as at most one such step per 0x80 clocks, the shortest speed-counter period
// the 0x0932 range allows), and a frequency-locked loop estimates the oscillator
// deviation (0x0932, 0.1 ppm per LSB, range +-(speed counter start - 0x7F)) over windows of
// 2^(0x0935 & 15) * 250 ns local time. 0x092C shows the difference averaged with weight
// 2^-(0x0934 & 15). Writing 0x0930 resets 0x092C and 0x0932. The loop never jumps the clock; a
// master sets 0x0920 first so that only small differences remain (32-bit comparison).
//
// SYNC0/SYNC1 (0x0980-0x09A7): with 0x0981 bit0 (cyclic operation) and bit1/bit2, the first SYNC0
// pulse is at the start time 0x0990 (system time), then every 0x09A0 ns (0 = single shot).
// SYNC1 fires 0x09A4 ns after the start time and then every max(1, 0x09A4 / 0x09A0) SYNC0
// cycles. The ESC fires when the system time reaches the start time, so a start time already in
// the past would only be met again after a wrap-around (4.3 s with 32-bit DC, never with 64
// bit): the unit stays pending (0x0984 bit0) with no deadline; masters (SOEM) set it in the
// future. With the start-time plausibility check (0x0981 bit5) such a start time instead
// starts generation immediately and sets 0x0984 bit2. 0x0981 bit3 activates on writing 0x0990, bit4
// extends a 32-bit start time to 64 bit. Pulse length 0x0982 = 0 is acknowledge mode: the
// status bit 0x098E/0x098F stays set until read.
//
// Register access: `now` is global time (Clock::now()); for ECAT accesses the ESC passes the time
// the frame's SOF passed port 0 (FrameTiming::port0_rx), so 0x0910 reads and compares use that
// instant, as the silicon latches the system time at SOF. Write permissions follow ET1100: sync
// out registers belong to ECAT or PDI per 0x0980 bit0, latch control per bits 4/5, the rest is
// ECAT-only. Latch units have registers only (no inputs yet). Nothing allocates.
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

  // Registers to reset values (the oscillator model, drift and start offset, is kept).
  void reset();

  // Register access; `offset` is relative to 0x0900, `in`/`out` stay within 0x0900-0x09FF.
  void read(std::uint16_t offset, std::span<std::uint8_t> out, Nanos now);
  void write(std::uint16_t offset, std::span<const std::uint8_t> in, Nanos now, bool from_ecat);

  // A frame wrote 0x0900: latch the receive time of that frame at each port (local time).
  // Ports with a negative time (closed) keep their previous value; a port whose time is
  // FrameTiming::kLater is latched by frame_returned().
  void latch_receive_times(const FrameTiming& timing);
  // The frame that last latched receive times came back in at `port` (1..3) at global time `now`:
  // latches it there if that port's time was kLater; otherwise (no latch pending) nothing changes.
  void frame_returned(int port, Nanos now);

  // EEPROM word 2 (ESC configuration area) loads the SYNC pulse length 0x0982 (10 ns units);
  // the register is read-only on both sides otherwise.
  void load_pulse_length(std::uint16_t ten_ns_units);

  // Model parameters: ppm drift of this ESC's oscillator, and its local time at global time 0.
  void set_drift_ppm(double ppm);
  void set_start_offset(Nanos local_at_zero);

  // Injected fault: the schedule runs on, but no SYNC0/SYNC1 pulse is driven (no event, no
  // 0x098E/0x098F status). Kept across reset(), like the oscillator model.
  void set_pulses_suppressed(bool suppressed) {
    ++version_;
    pulses_suppressed_ = suppressed;
  }

  // Local and system time at global time `now`.
  std::uint64_t local_time(Nanos now) const;
  std::uint64_t system_time(Nanos now) const;

  // Advance SYNC generation up to `now`; returns which SYNC signals fired since the last call.
  SyncEvents tick(Nanos now);
  // Global time of the next SYNC edge, or INT64_MAX if none is programmed.
  Nanos next_deadline() const;

private:
  // Time-control loop state; correction(L) = corr_anchor_ + freq_*(L - local_anchor_) + phase
  // slewed towards pending_phase_ since the anchor.
  double correction_at(std::int64_t local) const;
  void compare_system_time(std::uint32_t received, Nanos now);
  void reset_control_loop(Nanos now);
  // SYNC generation
  void activate(Nanos now);
  void schedule_after(std::uint64_t sys_now);
  Nanos global_time_of(std::uint64_t system) const;
  // Register helpers
  void refresh_dynamic(Nanos now, std::uint16_t offset, std::size_t len);  // registers a read covers
  bool writable(std::uint16_t reg, bool from_ecat) const;

  const Clock& clock_;
  std::uint8_t regs_[0x100] = {};
  std::uint8_t return_latches_ = 0;  // bit p: port p's receive time waits for frame_returned()
  double drift_ppm_ = 0.0;
  Nanos start_offset_ = 0;
  std::int64_t system_offset_ = 0;     // 0x0920
  std::uint32_t system_delay_ = 0;     // 0x0928

  double corr_anchor_ = 0.0;
  std::int64_t local_anchor_ = 0;
  double freq_ = 0.0;                 // correction rate, ns per local ns
  double pending_phase_ = 0.0;        // ns still to slew in, as of the anchor
  double diff_mean_ = 0.0;            // filtered system time difference (0x092C)
  bool fll_open_ = false;             // a frequency measurement window is running
  std::int64_t fll_local0_ = 0;       // window start: local time, difference and correction
  double fll_diff0_ = 0.0;
  double fll_corr0_ = 0.0;

  std::uint64_t start_time_ = 0;      // 0x0990 as written
  bool cyclic_active_ = false;        // 0x0981 bit0 accepted
  bool first_pulse_pending_ = false;  // 0x0984 bit0
  bool never_reached_ = false;        // start time in the past: no pulse until it is reached again
  std::uint64_t next_sync0_ = 0;      // system time of the next SYNC0 / SYNC1 pulse
  std::uint64_t next_sync1_ = 0;
  std::uint64_t sync1_period_ = 0;
  std::uint64_t last_sync0_ = 0;
  std::uint64_t last_sync1_ = 0;
  bool sync0_seen_ = false;
  bool sync1_seen_ = false;
  bool sync0_latched_ = false;        // acknowledge-mode status 0x098E / 0x098F
  bool sync1_latched_ = false;
  bool pulses_suppressed_ = false;

  // System time runs at the host clock's rate (no drift, no frequency or phase correction).
  bool host_rate() const;
  // global_time_of answers by integer arithmetic at host rate for edges closer than this (the
  // general path's doubles are exact there).
  static constexpr std::int64_t kHostRateSpan = std::int64_t{1} << 53;

  std::uint64_t version_ = 0;  // bumped by every call but read(), which cannot move the deadline
  mutable Nanos deadline_asked_at_ = INT64_MIN;  // next_deadline()'s last answer, for `now` and version_
  mutable std::uint64_t deadline_version_ = 0;
  mutable Nanos deadline_ = 0;
  mutable bool deadline_holds_ = false;  // deadline_ is a host-rate answer: valid until version_ moves
};

}  // namespace vdrive::esc
