#pragma once
// When the events a scenario can wait for happened (first occurrence; target_reached: the first
// after the slave's last set-point), so time points ({on: op, delay: 100ms}) resolve to times.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/scenario/scenario.hpp"

namespace vdrive::scenario {

class EventLog {
public:
  explicit EventLog(std::size_t slaves);

  void all_in_state(AlTarget state, Nanos now);   // preop / safeop / op
  // The drive's statusword this check; fires enabled, fault and target_reached.
  void statusword(int slave, std::uint16_t value, Nanos now);
  void set_point_given(int slave);                // re-arms target_reached
  void step_ran(const std::string& name, Nanos now);

  // The time `p` stands for, once its event happened.
  std::optional<Nanos> resolve(const TimePoint& p) const;

private:
  struct Slave {
    std::optional<Nanos> enabled, fault, target_reached;
    std::uint16_t last = 0;
    bool seen = false;
    bool armed = false;
  };
  std::optional<Nanos> preop_, safeop_, op_;
  std::vector<Slave> slaves_;
  std::map<std::string, Nanos> steps_;
};

}  // namespace vdrive::scenario
