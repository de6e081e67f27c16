#pragma once
// A command's --slave: a position (1 = first in cable order) or a station address ("0x1002"), as
// ethercat/slave_ref.hpp reads them; and the same slave in a control request's JSON.
#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>
#include <string>

namespace vdrive::cli {

// Refuses anything ecat::parse_slave_ref refuses, with its message.
CLI::Validator slave_ref_validator();
// The control protocol's two forms: a position as a number, an address as its text. `text` has
// passed the validator.
nlohmann::json slave_json(const std::string& text);

}  // namespace vdrive::cli
