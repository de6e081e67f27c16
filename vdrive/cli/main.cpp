#include <CLI/CLI.hpp>

#include "vdrive/cli/demo_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"vdrive: virtual EtherCAT servo drives"};
  vdrive::cli::add_demo_command(app);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
