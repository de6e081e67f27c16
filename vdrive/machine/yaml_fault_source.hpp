#pragma once
// A fault of a network file's `faults:` list, read with the fields fault::read_fault asks for
// (the scenario files' fields): `slave` also by a slave's name, every mistake as
// NetworkFileError "<file>:<line>: faults[i].FIELD: what", and a field the kind does not take
// refused by name.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vdrive/fault/fault_spec.hpp"

namespace vdrive::machine {

// `where` is "faults[2]"; `slave_names` in the file's order (positions count from 1).
// `extra_keys` are the entry's own keys besides the fault's (e.g. "at"), accepted as read.
fault::FaultSpec read_yaml_fault(const YAML::Node& entry, const std::string& file, const std::string& where,
                                 const std::vector<std::string>& slave_names,
                                 const std::vector<std::string>& extra_keys);

}  // namespace vdrive::machine
