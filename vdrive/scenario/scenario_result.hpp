#pragma once
// What one scenario run found: every expectation's verdict, the master's counters, and an error
// for a run that could not be carried out (the line never reached the start state, a fault that
// cannot act on its target).
#include <cstdint>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/scenario/expectation_check.hpp"

namespace vdrive::scenario {

// A host stall in a real-time run (runtime/host_stalls.hpp): when, how long, what the drives saw.
struct StallNote {
  Nanos time = 0;
  Nanos length = 0;
  std::string text;
};

struct ScenarioResult {
  std::string name;
  std::string file;
  std::vector<ExpectationResult> expectations;
  std::string error;                 // the run stopped early (expectations then still reported)
  std::vector<std::string> log;      // steps and faults as they happened, one line each
  Nanos simulated = 0;               // virtual time covered
  Nanos ended = 0;                   // when the run ended: what was still open was decided then
  double wall_seconds = 0.0;
  std::uint64_t cycles = 0, wrong_wkc = 0, lost_frames = 0;
  // Real time only: stalls of the host (counted; the first kMaxStallNotes described).
  std::uint64_t host_stalls = 0;
  Nanos longest_host_stall = 0;
  std::vector<StallNote> stalls;
  static constexpr std::size_t kMaxStallNotes = 100;

  std::size_t failed() const {
    std::size_t n = error.empty() ? 0 : 1;
    for (const auto& e : expectations) n += e.passed ? 0 : 1;
    return n;
  }
  bool passed() const { return failed() == 0; }
};

}  // namespace vdrive::scenario
