#pragma once
// Reads scenario files (schema: docs/scenarios.md). Strict: an unknown key, a missing one, a
// value of the wrong type or out of range, an unknown product, fault kind, event or step name all
// throw ScenarioError "<file>:<line>:<column>: <field path>: <what was wrong>", e.g.
//   "scenarios/a6b_op.yaml:14:11: timeline[2].fault.kind: unknown fault kind \"jamm\" (jam, ...)".
// Plant files named in the segment are read relative to the scenario file.
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/scenario/scenario.hpp"

namespace vdrive::scenario {

class ScenarioError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

Scenario parse_scenario(std::string_view text, const std::string& file);
Scenario load_scenario_file(const std::string& path);
// A file, or every *.yaml directly in a directory (sorted by name).
std::vector<std::string> scenario_files(const std::string& file_or_directory);

}  // namespace vdrive::scenario
