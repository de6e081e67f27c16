#pragma once
// JUnit XML for CI systems: one <testsuite> per scenario, one <testcase> per expectation (a
// scenario that could not run is one failed testcase named "run").
#include <string>
#include <vector>

#include "vdrive/scenario/scenario_result.hpp"

namespace vdrive::scenario {

// Throws std::runtime_error naming the file if it cannot be written.
void write_junit(const std::string& path, const std::vector<ScenarioResult>& results);

}  // namespace vdrive::scenario
