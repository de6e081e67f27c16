#pragma once
// Thrown by a subcommand to end the program with a one-line message on stderr
// ("vdrive: error: <what>") and a specific exit code. main() catches it.
#include <stdexcept>
#include <string>

#include "vdrive/cli/exit_codes.hpp"

namespace vdrive::cli {

class CliError : public std::runtime_error {
public:
  CliError(int exit_code, const std::string& what) : std::runtime_error(what), code_(exit_code) {}
  int exit_code() const { return code_; }

private:
  int code_;
};

}  // namespace vdrive::cli
