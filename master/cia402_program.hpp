#pragma once
// A CiA 402 program for the master's cyclic task, as a PLC's motion runtime would run it: in
// Pre-Op it maps the PDOs it needs (RxPDO 1600h: 6040h, 6060h, 607Ah; TxPDO 1A00h: 6041h, 6061h,
// 6064h, 60F4h, 603Fh — remapping as TwinCAT does, 1C12h/1C13h cleared first) and reads the
// following-error window 6065h; in the cycles it walks every drive through the power state
// machine (fault reset, shutdown, switch on, enable operation) in cyclic synchronous position
// mode with 607Ah tracking 6064h until enabled, waits `settle`, then commands
// 607Ah = start + amplitude * (1 - cos(2 pi f t)) — a sine that starts at rest, as a PLC's cam
// would, instead of a speed step at t = 0 — and records the drive's following error (60F4h).
// A drive that leaves Operation enabled meanwhile (a fault, or an AL error that disabled it) is
// reset (bit 7 edge; recovering, `reset_after` after the fault showed) and enabled again, and its motion starts again, at rest, from where the axis
// stands, so it gets no step; the sine still ends `motion` after the first start. With `recover`
// each drive's outages are counted (master/drive_recovery.hpp) and the verdict is whether it came
// back within `recovery_bound` every time, instead of whether it never faulted.
// After the sine it shuts every drive down (6040h = 0006h) and is done once none is in Operation
// enabled, so the master leaves Op without an ESM-change alarm (A6B Err88.2, DS5C1 E-882).
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "master/drive_recovery.hpp"
#include "master/op_run.hpp"

namespace vdrive::master {

class Master;

struct SineProgramOptions {
  Nanos cycle = 1'000'000;
  double amplitude = 0.0;        // user units; 0 = `revolutions` motor revolutions (608Fh / gear / feed)
  double revolutions = 1.0;      // used when amplitude is 0: each drive's own revolution
  double frequency_hz = 1.0;
  Nanos settle = 200'000'000;    // after Operation enabled, before the motion (A6B L9442: >= 100 ms)
  Nanos motion = 2'000'000'000;  // how long the sine runs
  bool recover = false;          // faults are expected: count outages, fail only on overdue ones
  Nanos recovery_bound = 10'000'000'000;  // a drive not enabled again by then did not come back
  Nanos reset_after = 250'000'000;        // recovering: how long a fault stands before the reset
};

struct DriveResult {
  std::uint16_t position = 0;           // 0-based, as Slave::position
  std::uint16_t station = 0;
  std::string name;                     // the SII's device name
  bool enabled = false;                 // reached Operation enabled
  bool faulted = false;                 // saw the fault bit after enabling
  std::uint16_t statusword = 0;         // 6041h when the sine ended (before the shutdown)
  std::uint16_t error_code = 0;         // 603Fh last seen
  std::uint32_t following_window = 0;   // 6065h
  std::int64_t max_following_error = 0; // max |60F4h| while the sine ran
  std::uint64_t samples = 0;            // cycles of sine measured
  double amplitude = 0.0;
  std::string note;                     // why the drive could not run the program
  bool recover = false;                 // SineProgramOptions::recover
  DriveRecovery recovery;               // its outages and how long each took
  bool ok() const {
    if (!enabled || samples == 0) return false;
    // Recovering, a fault or a following error beyond the window (which the drive reports as its
    // own alarm) is expected; what fails is a drive that did not come back in time.
    if (recover) return recovery.overdue() == 0;
    return !faulted && max_following_error <= following_window;
  }
};

// One line for a person: "slave 1 @0x1001 NAME: ok, amplitude ..., max following error ... (window 6065h =
// ...; position units of 6064h) over N cycles, statusword 0x..., 603Fh 0x...[: note]"; a failed
// drive says why: "FAILED (never reached Operation enabled)", "FAILED (faulted, 603Fh FF10h)",
// "FAILED (no sine cycle measured)", "FAILED (following error E beyond the window W)"; recovering,
// the outages follow: "; 3 outages, 3 recovered (603Fh FF18h x2, none x1), longest 412 ms" and
// "FAILED (not enabled again within 10000 ms: 1 outage)".
std::string describe(const DriveResult& r);
// "slave 1 @0x1001 NAME": how the drive's lines name it (ethercat/slave_ref.hpp).
std::string label(const DriveResult& r);

class SineProgram {
public:
  explicit SineProgram(const SineProgramOptions& options);

  void preop(Master& master);                    // OpRunOptions::preop
  void outputs(std::span<std::uint8_t> image);   // OpRunOptions::outputs
  void inputs(std::span<std::uint8_t> image);    // OpRunOptions::inputs
  // OpRunOptions::done: every drive ran its sine and has been shut down (out of Operation
  // enabled), so that the master's leaving Op raises no alarm.
  bool done() const;
  // Runs this program in `options` (preop, outputs, inputs, done); it must outlive the run.
  void attach(OpRunOptions& options);
  // Bus cycles of length `cycle` that settling and the sine take, with 5,000 to spare for enabling.
  std::uint64_t cycles_needed(Nanos cycle) const;
  // Drives with a mapped channel, and those of them in Operation enabled at the last cycle.
  std::size_t drives() const;
  std::size_t enabled_now() const;
  // Called in the cycle when a drive's outage starts, ends or becomes overdue (rare: a fault).
  using RecoveryCallback = std::function<void(const DriveResult&, DriveRecovery::Event)>;
  void on_recovery(RecoveryCallback cb) { on_recovery_ = std::move(cb); }

  const std::vector<DriveResult>& results() const { return results_; }

private:
  struct Channel {
    std::uint32_t cw = 0, mode = 0, target = 0;            // byte offsets in the image
    std::uint32_t status = 0, mode_display = 0, actual = 0, following = 0, error = 0;
    bool mapped = false;
    std::uint16_t last_cw = 0;
    std::int32_t start = 0;
    std::int32_t position = 0;
    std::uint16_t status_value = 0;
    Nanos enabled_at = -1;      // when the motion (re)started
    Nanos first_enabled_at = -1;  // the sine ends `motion` after this
    Nanos fault_since = -1;       // the fault bit has been set since
    bool enabled = false;       // Operation enabled in csp at the last cycle
    Nanos now = 0;
    bool finished = false;
  };
  void locate(std::span<std::uint8_t> image);

  SineProgramOptions options_;
  Master* master_ = nullptr;
  bool located_ = false;
  std::vector<Channel> channels_;
  std::vector<DriveResult> results_;
  RecoveryCallback on_recovery_;
};

}  // namespace vdrive::master
