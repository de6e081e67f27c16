#pragma once
// Decides one expectation from the values the runner measures at each check (every cycle):
//  at:     the first check at or after the time point decides;
//  by:     passes at the first check in [from, by] where the condition holds, fails after `by`;
//  always: fails at the first check in [from, until] where it does not hold.
// Time points that wait for an event that never happens fail with that reason at finish().
#include <cstdint>
#include <optional>
#include <string>

#include "common/clock.hpp"
#include "vdrive/scenario/event_log.hpp"
#include "vdrive/scenario/scenario.hpp"

namespace vdrive::scenario {

struct ExpectationResult {
  std::string name;
  int line = 0;
  bool passed = false;
  bool decided = false;
  Nanos time = 0;            // when it was decided
  std::string message;       // what was seen (failures: what was expected instead)
};

bool holds(const Condition& c, std::int64_t value);
std::string describe(const Condition& c);

class ExpectationCheck {
public:
  explicit ExpectationCheck(const Expectation& e);

  void check(Nanos now, std::int64_t value, const EventLog& events);
  // End of the run at `end`: what is still open is decided.
  void finish(Nanos end, const EventLog& events);

  const Expectation& expectation() const { return e_; }
  const ExpectationResult& result() const { return r_; }

private:
  void decide(bool passed, Nanos now, std::string message);

  const Expectation& e_;
  ExpectationResult r_;
  std::optional<std::int64_t> last_;
  std::uint64_t checks_ = 0;
};

}  // namespace vdrive::scenario
