// Distributed clocks of an ET1100-class ESC; see dc_unit.hpp for the time model.
#include "esc_model/dc_unit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/round.hpp"
#include "ethercat/little_endian.hpp"
#include "ethercat/registers.hpp"

namespace vdrive::esc {
namespace {

// Offsets inside the DC window: regs_ holds 0x0900-0x09FF.
constexpr std::uint16_t window(ecat::reg::Addr address) {
  return static_cast<std::uint16_t>(address - ecat::reg::kDcFirst);
}
constexpr std::uint16_t kReceiveTimePort0 = window(ecat::reg::kDcReceiveTimePort0);
constexpr std::uint16_t kSystemTime = window(ecat::reg::kDcSystemTime);
constexpr std::uint16_t kReceiveTimeEpu = window(ecat::reg::kDcReceiveTimeEpu);
constexpr std::uint16_t kSystemTimeOffset = window(ecat::reg::kDcSystemTimeOffset);
constexpr std::uint16_t kSystemTimeDelay = window(ecat::reg::kDcSystemTimeDelay);
constexpr std::uint16_t kSystemTimeDifference = window(ecat::reg::kDcSystemTimeDifference);
constexpr std::uint16_t kSpeedCounterStart = window(ecat::reg::kDcSpeedCounterStart);
constexpr std::uint16_t kSpeedCounterDiff = window(ecat::reg::kDcSpeedCounterDiff);
constexpr std::uint16_t kDifferenceFilterDepth = window(ecat::reg::kDcDifferenceFilterDepth);
constexpr std::uint16_t kSpeedFilterDepth = window(ecat::reg::kDcSpeedFilterDepth);
constexpr std::uint16_t kCyclicUnitControl = window(ecat::reg::kDcCyclicUnitControl);
constexpr std::uint16_t kActivation = window(ecat::reg::kDcActivation);
constexpr std::uint16_t kPulseLength = window(ecat::reg::kDcPulseLength);
constexpr std::uint16_t kActivationStatus = window(ecat::reg::kDcActivationStatus);
constexpr std::uint16_t kSync0Status = window(ecat::reg::kDcSync0Status);
constexpr std::uint16_t kSync1Status = window(ecat::reg::kDcSync1Status);
constexpr std::uint16_t kStartTime = window(ecat::reg::kDcStartTime);
constexpr std::uint16_t kNextSync1 = window(ecat::reg::kDcNextSync1);
constexpr std::uint16_t kSync0CycleTime = window(ecat::reg::kDcSync0CycleTime);
constexpr std::uint16_t kSync1CycleTime = window(ecat::reg::kDcSync1CycleTime);
constexpr std::uint16_t kLatch0Control = window(ecat::reg::kDcLatch0Control);
constexpr std::uint16_t kLatch1Control = window(ecat::reg::kDcLatch1Control);

using namespace ecat::reg::dc_cyclic_unit_control;
using namespace ecat::reg::dc_activation_status;
constexpr std::uint8_t kCyclicOperation = ecat::reg::dc_activation::kCyclicOperation;
constexpr std::uint8_t kSync0Enable = ecat::reg::dc_activation::kSync0;
constexpr std::uint8_t kSync1Enable = ecat::reg::dc_activation::kSync1;
constexpr std::uint8_t kAutoActivation = ecat::reg::dc_activation::kAutoActivation;
constexpr std::uint8_t kStartTimeExtension = ecat::reg::dc_activation::kStartTimeExtension;
constexpr std::uint8_t kPlausibilityCheck = ecat::reg::dc_activation::kPlausibilityCheck;
constexpr std::uint8_t kNearFuture2s = ecat::reg::dc_activation::kNearFuture2s;

constexpr std::uint16_t kSpeedCounterStartReset = 0x1000;
constexpr std::uint16_t kSpeedCounterMinDelta = 0x7F;
constexpr double kPpmPerSpeedLsb = 0.1;
// The ET1100 corrects its copy of system time by one ns at most every 0x80 periods of 10 ns.
constexpr double kMaxSlew = 1.0 / (0x80 * 10.0);
// Frequency measurement window: 2^(0x0935 depth) * this; 1 ms at the reset depth of 12.
constexpr std::int64_t kFllWindowUnit = 250;
constexpr double kFllGain = 0.5;
constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

using ecat::get_le;
using ecat::put_le;

bool overlaps(std::uint16_t offset, std::size_t len, std::uint16_t first, std::uint16_t size) {
  return offset < first + size && first < offset + len;
}

}  // namespace

DcUnit::DcUnit(const Clock& clock) : clock_(clock) { reset(); }

void DcUnit::reset() {
  ++version_;
  std::fill(std::begin(regs_), std::end(regs_), 0);
  put_le(&regs_[kSpeedCounterStart], kSpeedCounterStartReset, 2);
  regs_[kDifferenceFilterDepth] = 0x04;
  regs_[kSpeedFilterDepth] = 0x0C;
  return_latches_ = 0;
  system_offset_ = 0;
  system_delay_ = 0;
  corr_anchor_ = 0.0;
  local_anchor_ = 0;
  freq_ = 0.0;
  pending_phase_ = 0.0;
  reset_control_loop(clock_.now());
  start_time_ = 0;
  cyclic_active_ = false;
  first_pulse_pending_ = false;
  never_reached_ = false;
  next_sync0_ = next_sync1_ = kNever;
  sync1_period_ = 0;
  last_sync0_ = last_sync1_ = 0;
  sync0_seen_ = sync1_seen_ = false;
  sync0_latched_ = sync1_latched_ = false;
}

// ---- time ----------------------------------------------------------------------------------

void DcUnit::set_drift_ppm(double ppm) {
  ++version_;
  drift_ppm_ = ppm;
}
void DcUnit::set_start_offset(Nanos local_at_zero) {
  ++version_;
  start_offset_ = local_at_zero;
}

std::uint64_t DcUnit::local_time(Nanos now) const {
  if (drift_ppm_ == 0.0) return static_cast<std::uint64_t>(start_offset_ + now);  // read on every deadline query
  const auto drift = static_cast<std::int64_t>(round_to_int64(static_cast<double>(now) * drift_ppm_ * 1e-6));
  return static_cast<std::uint64_t>(start_offset_ + now + drift);
}

double DcUnit::correction_at(std::int64_t local) const {
  const double dl = static_cast<double>(local - local_anchor_);
  double c = corr_anchor_ + freq_ * dl;
  if (dl > 0 && pending_phase_ != 0.0) c += std::copysign(std::min(std::fabs(pending_phase_), kMaxSlew * dl), pending_phase_);
  return c;
}

std::uint64_t DcUnit::system_time(Nanos now) const {
  const auto local = static_cast<std::int64_t>(local_time(now));
  return static_cast<std::uint64_t>(local + system_offset_ + round_to_int64(correction_at(local)));
}

void DcUnit::reset_control_loop(Nanos now) {
  // Keep the correction accumulated so far (the clock does not jump); forget what was learned.
  const auto local = static_cast<std::int64_t>(local_time(now));
  corr_anchor_ = correction_at(local);
  local_anchor_ = local;
  freq_ = 0.0;
  pending_phase_ = 0.0;
  diff_mean_ = 0.0;
  fll_open_ = false;
}

void DcUnit::compare_system_time(std::uint32_t received, Nanos now) {
  const auto local = static_cast<std::int64_t>(local_time(now));
  const double corr = correction_at(local);
  const auto copy = static_cast<std::uint64_t>(local + system_offset_ + round_to_int64(corr));
  // Positive: the local copy is ahead of the reference (as it arrives here, delay included).
  const auto diff = static_cast<std::int32_t>(static_cast<std::uint32_t>(copy) - (received + system_delay_));

  // Frequency-locked loop: over a window, the reference advanced by (local advance + correction
  // applied - change of the difference); the ideal rate makes our correction match that.
  const std::int64_t window = std::int64_t{1} << (regs_[kSpeedFilterDepth] & 0x0F);
  if (!fll_open_) {
    fll_open_ = true;
    fll_local0_ = local;
    fll_diff0_ = diff;
    fll_corr0_ = corr;
  } else if (local - fll_local0_ >= window * kFllWindowUnit) {
    const double dl = static_cast<double>(local - fll_local0_);
    const double ideal = ((corr - fll_corr0_) - (diff - fll_diff0_)) / dl;
    const double start = static_cast<double>(get_le(&regs_[kSpeedCounterStart], 2) & 0x7FFF);
    const double limit = std::max(0.0, start - kSpeedCounterMinDelta) * kPpmPerSpeedLsb * 1e-6;
    freq_ = std::clamp(freq_ + kFllGain * (ideal - freq_), -limit, limit);
    fll_local0_ = local;
    fll_diff0_ = diff;
    fll_corr0_ = corr;
  }

  // Phase: slew the whole difference out, starting now.
  corr_anchor_ = corr;
  local_anchor_ = local;
  pending_phase_ = -static_cast<double>(diff);

  const int depth = regs_[kDifferenceFilterDepth] & 0x0F;
  diff_mean_ += (diff - diff_mean_) / static_cast<double>(1 << depth);
}

void DcUnit::latch_receive_times(const FrameTiming& timing) {
  ++version_;
  const Nanos ports[4] = {timing.port0_rx, timing.port1_rx, timing.port2_rx, timing.port3_rx};
  return_latches_ = 0;
  for (int p = 0; p < 4; ++p) {
    if (ports[p] == FrameTiming::kLater) return_latches_ |= static_cast<std::uint8_t>(1U << p);
    if (ports[p] < 0) continue;
    put_le(&regs_[kReceiveTimePort0 + 4 * p], local_time(ports[p]), 4);
  }
  if (timing.port0_rx >= 0) put_le(&regs_[kReceiveTimeEpu], local_time(timing.port0_rx), 8);
}

void DcUnit::frame_returned(int port, Nanos now) {
  if (port < 1 || port > 3 || (return_latches_ & (1U << port)) == 0) return;
  ++version_;
  return_latches_ = static_cast<std::uint8_t>(return_latches_ & ~(1U << port));
  put_le(&regs_[kReceiveTimePort0 + 4 * port], local_time(now), 4);
}

void DcUnit::load_pulse_length(std::uint16_t ten_ns_units) {
  ++version_;
  put_le(&regs_[kPulseLength], ten_ns_units, 2);
}

// ---- registers -----------------------------------------------------------------------------

// Only the registers a read covers are computed: the firmware reads the system time on every
// control step, and the rest (filters, pulse status) would cost as much again each time.
void DcUnit::refresh_dynamic(Nanos now, std::uint16_t offset, std::size_t len) {
  const auto covered = [&](std::uint16_t first, std::uint16_t size) {
    return overlaps(offset, len, first, size);
  };
  if (covered(kSystemTime, 8)) put_le(&regs_[kSystemTime], system_time(now), 8);

  if (covered(kSystemTimeDifference, 4)) {
    const auto mean = static_cast<std::int64_t>(std::llround(diff_mean_));
    const std::uint64_t magnitude = std::min<std::uint64_t>(static_cast<std::uint64_t>(mean < 0 ? -mean : mean), 0x7FFFFFFF);
    put_le(&regs_[kSystemTimeDifference], magnitude | (mean < 0 ? 0x80000000u : 0u), 4);
  }

  if (covered(kSpeedCounterDiff, 2)) {
    const auto start = static_cast<std::int64_t>(get_le(&regs_[kSpeedCounterStart], 2) & 0x7FFF);
    const std::int64_t range = std::max<std::int64_t>(0, start - kSpeedCounterMinDelta);
    const std::int64_t speed = std::clamp<std::int64_t>(std::llround(freq_ * 1e6 / kPpmPerSpeedLsb), -range, range);
    put_le(&regs_[kSpeedCounterDiff], static_cast<std::uint64_t>(speed), 2);
  }

  if (covered(kActivationStatus, 1)) {
    std::uint8_t status = regs_[kActivationStatus] & kStartTimeImplausible;
    if (first_pulse_pending_) status |= kSync0Pending;
    if (cyclic_active_ && !sync1_seen_ && next_sync1_ != kNever) status |= kSync1Pending;
    regs_[kActivationStatus] = status;
  }

  if (covered(kSync0Status, 1) || covered(kSync1Status, 1)) {
    const std::uint64_t pulse = get_le(&regs_[kPulseLength], 2) * 10;
    if (pulse == 0) {
      regs_[kSync0Status] = sync0_latched_ ? 1 : 0;
      regs_[kSync1Status] = sync1_latched_ ? 1 : 0;
    } else {
      const std::uint64_t sys = system_time(now);
      regs_[kSync0Status] = (!pulses_suppressed_ && sync0_seen_ && sys >= last_sync0_ && sys - last_sync0_ < pulse) ? 1 : 0;
      regs_[kSync1Status] = (!pulses_suppressed_ && sync1_seen_ && sys >= last_sync1_ && sys - last_sync1_ < pulse) ? 1 : 0;
    }
  }

  if (covered(kStartTime, 8)) {
    put_le(&regs_[kStartTime], cyclic_active_ && next_sync0_ != kNever ? next_sync0_ : start_time_, 8);
  }
  if (covered(kNextSync1, 8)) put_le(&regs_[kNextSync1], cyclic_active_ && next_sync1_ != kNever ? next_sync1_ : 0, 8);
}

void DcUnit::read(std::uint16_t offset, std::span<std::uint8_t> out, Nanos now) {
  if (offset >= kSystemTime && offset + out.size() <= kSystemTime + 8u) {
    // The system time alone (firmware reads it every control step): no other register is touched.
    put_le(&regs_[kSystemTime], system_time(now), 8);
    std::copy_n(&regs_[offset], out.size(), out.begin());
    return;
  }
  refresh_dynamic(now, offset, out.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = offset + i < sizeof(regs_) ? regs_[offset + i] : 0;
  // Acknowledge mode: reading the SYNC status clears it.
  if (get_le(&regs_[kPulseLength], 2) == 0) {
    if (overlaps(offset, out.size(), kSync0Status, 1)) sync0_latched_ = false;
    if (overlaps(offset, out.size(), kSync1Status, 1)) sync1_latched_ = false;
  }
}

bool DcUnit::writable(std::uint16_t reg, bool from_ecat) const {
  const std::uint8_t owner = regs_[kCyclicUnitControl];
  if (reg == kActivation || (reg >= kStartTime && reg < kStartTime + 8) ||
      (reg >= kSync0CycleTime && reg < kSync1CycleTime + 4))
    return from_ecat == !(owner & kSyncOutPdi);
  if (reg == kLatch0Control) return from_ecat == !(owner & kLatch0Pdi);
  if (reg == kLatch1Control) return from_ecat == !(owner & kLatch1Pdi);
  if (!from_ecat) return false;
  return (reg >= kSystemTimeOffset && reg < kSystemTimeDifference) ||
         (reg >= kSpeedCounterStart && reg < kSpeedCounterStart + 2) || reg == kDifferenceFilterDepth ||
         reg == kSpeedFilterDepth || reg == kCyclicUnitControl;
}

void DcUnit::write(std::uint16_t offset, std::span<const std::uint8_t> in, Nanos now, bool from_ecat) {
  ++version_;
  const std::size_t len = in.size();
  std::uint8_t start_bytes[8];
  put_le(start_bytes, start_time_, 8);
  bool start_written = false;
  bool start_high_written = false;
  const bool was_active = cyclic_active_;

  for (std::size_t i = 0; i < len && offset + i < sizeof(regs_); ++i) {
    const auto reg = static_cast<std::uint16_t>(offset + i);
    if (!writable(reg, from_ecat)) continue;
    if (reg >= kStartTime && reg < kStartTime + 8) {
      start_bytes[reg - kStartTime] = in[i];
      start_written = true;
      start_high_written |= reg >= kStartTime + 4;
      continue;
    }
    regs_[reg] = in[i];
  }
  regs_[kSpeedCounterStart + 1] &= 0x7F;
  regs_[kDifferenceFilterDepth] &= 0x0F;
  regs_[kSpeedFilterDepth] &= 0x0F;

  // Time control: a write reaching 0x0910 compares the written low 32 bits (unwritten bytes taken
  // from the local copy) with the local copy at this frame's SOF.
  if (from_ecat && overlaps(offset, len, kSystemTime, 1)) {
    std::uint8_t received[4];
    put_le(received, system_time(now), 4);
    for (std::size_t i = 0; i < len; ++i)
      if (offset + i >= kSystemTime && offset + i < kSystemTime + 4u) received[offset + i - kSystemTime] = in[i];
    compare_system_time(static_cast<std::uint32_t>(get_le(received, 4)), now);
  }
  if (from_ecat && overlaps(offset, len, kSystemTimeOffset, 8)) {
    system_offset_ = static_cast<std::int64_t>(get_le(&regs_[kSystemTimeOffset], 8));
    fll_open_ = false;  // the difference jumps with the offset; restart the frequency window
  }
  if (from_ecat && overlaps(offset, len, kSystemTimeDelay, 4))
    system_delay_ = static_cast<std::uint32_t>(get_le(&regs_[kSystemTimeDelay], 4));
  if (from_ecat && overlaps(offset, len, kSpeedCounterStart, 2)) reset_control_loop(now);

  if (start_written) {
    std::uint64_t start = get_le(start_bytes, 8);
    if (!start_high_written && (regs_[kActivation] & kStartTimeExtension)) {
      // 32-bit start time: take the upper half from the system time, the next such time ahead.
      const std::uint64_t sys = system_time(now);
      start = (sys & ~std::uint64_t{0xFFFFFFFF}) | (start & 0xFFFFFFFF);
      if (start < sys) start += std::uint64_t{1} << 32;
    }
    start_time_ = start;
    if (regs_[kActivation] & kAutoActivation) {
      regs_[kActivation] |= kCyclicOperation;
      activate(now);
      return;
    }
  }
  if (overlaps(offset, len, kActivation, 1) && writable(kActivation, from_ecat)) {
    if (!(regs_[kActivation] & kCyclicOperation)) {
      cyclic_active_ = false;
      first_pulse_pending_ = false;
      never_reached_ = false;
      next_sync0_ = next_sync1_ = kNever;
    } else if (!was_active) {
      activate(now);
    }
  }
}

// ---- SYNC generation -----------------------------------------------------------------------

void DcUnit::activate(Nanos now) {
  const std::uint64_t sys = system_time(now);
  const std::uint8_t act = regs_[kActivation];
  regs_[kActivationStatus] &= static_cast<std::uint8_t>(~kStartTimeImplausible);
  std::uint64_t start = start_time_;
  const std::uint64_t near = (act & kNearFuture2s) ? (std::uint64_t{1} << 31) : (std::uint64_t{1} << 63);
  const bool in_near_future = start > sys && start - sys <= near;
  never_reached_ = false;
  if (!in_near_future && (act & kPlausibilityCheck)) {
    start = sys;  // immediate SyncSignal generation
    regs_[kActivationStatus] |= kStartTimeImplausible;
  } else if (start <= sys) {
    never_reached_ = true;  // a 64-bit system time does not come back to a past start time
  }
  cyclic_active_ = true;
  first_pulse_pending_ = true;
  sync0_seen_ = sync1_seen_ = false;
  const std::uint64_t cycle0 = get_le(&regs_[kSync0CycleTime], 4);
  const std::uint64_t cycle1 = get_le(&regs_[kSync1CycleTime], 4);
  next_sync0_ = start;
  next_sync1_ = start > kNever - cycle1 ? kNever : start + cycle1;
  sync1_period_ = cycle0 == 0 ? 0 : std::max<std::uint64_t>(1, cycle1 / cycle0) * cycle0;
}

SyncEvents DcUnit::tick(Nanos now) {
  ++version_;
  SyncEvents events;
  if (!cyclic_active_ || never_reached_) return events;
  const std::uint64_t sys = system_time(now);
  const std::uint8_t act = regs_[kActivation];

  if (next_sync0_ != kNever && sys >= next_sync0_) {
    first_pulse_pending_ = false;
    last_sync0_ = next_sync0_;
    sync0_seen_ = true;
    if ((act & kSync0Enable) && !pulses_suppressed_) {
      events.sync0 = true;
      sync0_latched_ = true;
    }
    const std::uint64_t cycle0 = get_le(&regs_[kSync0CycleTime], 4);
    // Late tick: pulses in between are merged into this one (the firmware sees one event).
    next_sync0_ = cycle0 == 0 ? kNever : next_sync0_ + cycle0 * (1 + (sys - next_sync0_) / cycle0);
  }
  if (next_sync1_ != kNever && sys >= next_sync1_) {
    last_sync1_ = next_sync1_;
    sync1_seen_ = true;
    if ((act & kSync1Enable) && !pulses_suppressed_) {
      events.sync1 = true;
      sync1_latched_ = true;
    }
    next_sync1_ = sync1_period_ == 0 ? kNever : next_sync1_ + sync1_period_ * (1 + (sys - next_sync1_) / sync1_period_);
  }
  return events;
}

Nanos DcUnit::next_deadline() const {
  if (!cyclic_active_ || never_reached_) return INT64_MAX;
  const std::uint8_t act = regs_[kActivation];
  std::uint64_t target = kNever;
  if ((act & kSync0Enable) || first_pulse_pending_) target = std::min(target, next_sync0_);
  if (act & kSync1Enable) target = std::min(target, next_sync1_);
  if (target == kNever) return INT64_MAX;
  // Asked for every slave in every round of the loop. At host rate (no drift, no correction)
  // system time is host time plus a constant, so the answer is one fixed instant whenever it is
  // asked, before the edge or after it (global_time_of's two paths give the same number): it
  // holds until the unit changes, without reading the clock. Otherwise the answer depends on
  // `now` and the unit's state, and is reused while neither changed. Exact, not an approximation.
  if (deadline_holds_ && version_ == deadline_version_) return deadline_;
  const Nanos now = clock_.now();
  if (version_ != deadline_version_ || now != deadline_asked_at_) {
    deadline_ = global_time_of(target);
    deadline_asked_at_ = now;
    deadline_version_ = version_;
    deadline_holds_ = host_rate() && deadline_ > now && deadline_ - now < kHostRateSpan;
  }
  return deadline_;
}

bool DcUnit::host_rate() const { return drift_ppm_ == 0.0 && freq_ == 0.0 && pending_phase_ == 0.0; }

Nanos DcUnit::global_time_of(std::uint64_t system) const {
  const Nanos now = clock_.now();
  const auto local0 = static_cast<std::int64_t>(local_time(now));
  const std::uint64_t sys0 = system_time(now);
  if (system <= sys0) {
    // Already due: answer the edge's own (past) time, not this clock reading. A caller compares
    // the deadline with a `now` it read *before* calling; with a real clock that reading is always
    // a little earlier than ours, so "now" here would never count as due and SYNC0 would stall.
    const std::uint64_t late = sys0 - system;
    constexpr auto kFar = static_cast<std::uint64_t>(INT64_MAX / 4);
    return late > kFar ? INT64_MIN / 4 : now - static_cast<Nanos>(late);
  }
  // Beyond this horizon (about 146 years) nobody waits for the edge; also keeps the math finite.
  constexpr std::uint64_t kHorizon = std::uint64_t{1} << 62;
  if (system - sys0 > kHorizon) return INT64_MAX;
  // No drift, no correction: system time is host time plus a constant. What the general path
  // below computes is then exactly `need` ns from now, as long as `need` is exact in a double.
  if (host_rate() && system - sys0 < static_cast<std::uint64_t>(kHostRateSpan)) return now + static_cast<Nanos>(system - sys0);
  const double need = static_cast<double>(system - sys0);

  // System time runs at (1 + freq) per local ns, plus the remaining phase slew while it lasts.
  const double since_anchor = static_cast<double>(std::max<std::int64_t>(0, local0 - local_anchor_));
  const double applied = std::copysign(std::min(std::fabs(pending_phase_), kMaxSlew * since_anchor), pending_phase_);
  const double remaining = pending_phase_ - applied;
  const double slew_time = std::fabs(remaining) / kMaxSlew;
  const double slew_rate = 1.0 + freq_ + std::copysign(kMaxSlew, remaining);
  double local_needed;
  if (remaining == 0.0 || need <= slew_rate * slew_time) {
    local_needed = need / (remaining == 0.0 ? 1.0 + freq_ : slew_rate);
  } else {
    local_needed = slew_time + (need - slew_rate * slew_time) / (1.0 + freq_);
  }
  const std::int64_t local_target = local0 + static_cast<std::int64_t>(std::ceil(local_needed));

  // Invert the oscillator model, then step to the first global ns whose local time is there.
  const double rate = 1.0 + drift_ppm_ * 1e-6;
  Nanos t = now + static_cast<Nanos>(std::floor(static_cast<double>(local_target - local0) / rate));
  while (static_cast<std::int64_t>(local_time(t)) < local_target) ++t;
  return std::max(t, now + 1);
}

}  // namespace vdrive::esc
