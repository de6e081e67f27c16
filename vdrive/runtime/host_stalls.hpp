#pragma once
// Host stalls (docs/reliability.md "Host stalls"): in real time, the event loop runs the line's
// timers (SYNC0 pulses, the drives' control steps, watchdogs) at their deadlines. When it gets to
// them later than a threshold, the host (or the VM under it) did not run the loop's thread for
// that long, and the drives saw it: SYNC0 pulses merged into one, control steps caught up at
// once, set-points the master sent meanwhile taken in a burst. HostStalls names such a stall: a
// counter, the longest, and a record of each (when, how late, what the drives saw) that other
// threads read to put it in the status line, the log, telemetry, the web page's events and a
// scenario's report, and to say that a fault which follows one came "after a host stall of 12.3 ms".
//
// The loop does the detection (serve_once): plan() the network's next deadline before it waits,
// check() when it runs again; a lateness beyond floor() is then looked at more closely (the line's
// bus cycle, which drives were due), which is rare. One compare per loop round otherwise; no lock,
// no allocation. Virtual time (run_until) never stalls and never calls these.
//
// Threads: one writer (the loop's thread: plan, check, record), any number of readers. Counters
// are single-writer atomics; the last kLog records sit in a ring whose slots carry their record's
// number, written after the record and read before and after it (a sequence lock), so a reader
// never takes a half-written record for a whole one.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include "common/clock.hpp"

namespace vdrive::network { class Network; }

namespace vdrive::runtime {

// Default floor of the threshold: the kernel's ordinary wake-up latency on a shared host or VM
// reaches a few hundred microseconds; the drives tolerate that, and it is not a stall.
constexpr Nanos kDefaultStallFloor = 1'000'000;
// The threshold is max(floor, kStallCycles x the line's shortest bus cycle): at two cycles late a
// whole cycle passed in which the drives got neither their SYNC0 pulse nor the master's set-point.
constexpr int kStallCycles = 2;
// A fault noticed this soon after a stall ended is said to follow it ("after a host stall of ...").
constexpr Nanos kStallAftermath = 1'000'000'000;

// One stall and what the drives saw. Slaves are in cable order, bit i = slave i + 1 (the first 64).
struct HostStall {
  std::uint64_t number = 0;  // 1, 2, ... (0: none)
  Nanos time = 0;            // when the loop ran again (the loop's clock)
  Nanos length = 0;          // how late it ran the line's timers
  Nanos threshold = 0;       // what it was compared with
  Nanos cycle = 0;           // the line's shortest bus cycle then (0: none known)
  std::uint64_t sync0_slaves = 0;  // slaves in DC mode whose SYNC0 pulse was overdue
  std::uint32_t sync0_pulses = 0;  // the most SYNC0 pulses one of them had due (seen as one)
  std::uint64_t step_slaves = 0;   // drives whose control step was overdue
  std::uint32_t control_steps = 0; // the most control periods one of them was behind
};

class HostStalls {
public:
  static constexpr std::size_t kLog = 16;  // records kept for readers that look now and then

  // The lateness below which nothing is looked at (before serving; the loop thread reads it).
  void set_floor(Nanos floor) { floor_.store(floor, std::memory_order_relaxed); }
  Nanos floor() const { return floor_.load(std::memory_order_relaxed); }

  // Loop thread. plan(): the loop means to run its timers at `when` (kNever: none due). check():
  // the loop is at `now` and has not planned again since; records a stall (once per plan) if it
  // is late beyond the threshold. The loop checks when a round starts and again after running
  // timers, so time lost inside a round (a service, the firmware) is seen before it plans anew.
  // restart(): forget the plan (a loop that starts serving after a pause is not late).
  void plan(Nanos when) { planned_ = when; }
  void restart() { planned_ = kNever; }
  void check(network::Network& network, Nanos now) {
    if (planned_ != kNever && now - planned_ > floor_.load(std::memory_order_relaxed)) look(network, now);
  }
  // Loop thread: publishes `stall` (its number is set here). For check(), and for tests.
  void record(HostStall stall);

  // Any thread.
  std::uint64_t count() const { return count_.load(std::memory_order_acquire); }
  Nanos longest() const { return longest_.load(std::memory_order_relaxed); }
  // Record `number` (1-based) if the ring still holds it.
  std::optional<HostStall> get(std::uint64_t number) const;
  std::optional<HostStall> latest() const { return get(count()); }
  // The longest of the stalls that ended at most kStallAftermath before `now` and not after it
  // (same clock as the loop's); none if there is none.
  std::optional<HostStall> just_before(Nanos now) const;

private:
  static constexpr Nanos kNever = std::numeric_limits<Nanos>::max();
  void look(network::Network& network, Nanos now);

  struct Slot {
    std::atomic<std::uint64_t> number{0};  // 0 while being written
    std::atomic<Nanos> time{0}, length{0}, threshold{0}, cycle{0};
    std::atomic<std::uint64_t> sync0_slaves{0}, step_slaves{0};
    std::atomic<std::uint32_t> sync0_pulses{0}, control_steps{0};
  };

  Nanos planned_ = kNever;  // loop thread only
  std::atomic<Nanos> floor_{kDefaultStallFloor};
  std::atomic<std::uint64_t> count_{0};
  std::atomic<Nanos> longest_{0};
  std::array<Slot, kLog> ring_{};
};

// "host stall 12.3 ms (threshold 2.0 ms): slaves 1-3 got 1 of 12 SYNC0 pulses, drives 1-3 ran 12
// control periods late" into `out` (NUL-terminated, cut to fit; no allocation: for the loop
// thread). Returns the characters written. `slaves_before`: the slaves of the line before this
// process's (a later part of `vdrive run --processes`), so slaves are named by whole-line position.
std::size_t describe(const HostStall& stall, std::span<char> out, std::size_t slaves_before = 0);
std::string describe(const HostStall& stall, std::size_t slaves_before = 0);
// " after a host stall of 12.3 ms" for a fault line, when `stall` is one.
std::string after_stall(const std::optional<HostStall>& stall);
// "12.3 ms"
std::string stall_ms(Nanos length);

}  // namespace vdrive::runtime
