#include "master/tool/slave_option.hpp"

#include <stdexcept>

namespace vdrive::master::tool {

CLI::Option* add_slave_option(CLI::App* cmd, std::string& text) {
  const CLI::Validator slave_ref([](std::string& value) { return ecat::slave_ref_problem(value); }, "N|0xADDR");
  return cmd->add_option("--slave", text, "The slave: its position as scan prints it (1 = first) or its station address (0x1001)")
      ->required()
      ->check(slave_ref);
}

std::size_t resolve_slave(const Master& master, const std::string& text) {
  try {
    return find_slave(master, ecat::parse_slave_ref(text));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--slave " + text + ": " + e.what());
  }
}

}  // namespace vdrive::master::tool
