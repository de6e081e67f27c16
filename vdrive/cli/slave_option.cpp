#include "vdrive/cli/slave_option.hpp"

#include "ethercat/slave_ref.hpp"

namespace vdrive::cli {

CLI::Validator slave_ref_validator() {
  return CLI::Validator([](std::string& value) { return ecat::slave_ref_problem(value); }, "N|0xADDR");
}

nlohmann::json slave_json(const std::string& text) {
  const ecat::SlaveRef ref = ecat::parse_slave_ref(text);
  if (ref.is_address()) return text;
  return ref.value;
}

}  // namespace vdrive::cli
