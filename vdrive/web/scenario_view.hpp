#pragma once
// A real-time scenario's progress as the page shows it: its log so far and each expectation as it
// is decided.
#include <string>
#include <vector>

#include "common/clock.hpp"

namespace vdrive::web {

struct ExpectationView {
  int line = 0;       // in the scenario file
  std::string name;
  std::string state = "open";  // open, met, missed
  std::string detail;          // what was seen
};

struct ScenarioView {
  std::string name;
  std::string state = "running";  // running, passed, failed, error
  Nanos elapsed = 0, duration = 0;
  Nanos started = 0;  // on the line's clock; 0: unknown
  std::vector<std::string> log;
  std::vector<ExpectationView> expectations;
};

}  // namespace vdrive::web
