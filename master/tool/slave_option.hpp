#pragma once
// --slave for every vdrive-master command that acts on one slave: a position as scan prints it
// (1 = first) or a station address ("0x1002"), as vdrive's own commands take it
// (ethercat/slave_ref.hpp). A malformed value is a bad command line (exit 2); a slave the line does
// not have is found only after the scan.
#include <CLI/CLI.hpp>

#include <cstddef>
#include <string>

#include "master/master.hpp"

namespace vdrive::master::tool {

CLI::Option* add_slave_option(CLI::App* cmd, std::string& text);

// The index into master.slaves() of the slave `text` names; std::invalid_argument
// ("--slave 5: there is no slave 5: the line has slaves 1 to 3") when there is none.
std::size_t resolve_slave(const Master& master, const std::string& text);

}  // namespace vdrive::master::tool
