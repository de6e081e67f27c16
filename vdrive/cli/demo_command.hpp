#pragma once
// `vdrive demo`: creates a veth pair, serves a default line of drives on one end and drives it
// with the built-in master from the other, printing what a user would want to see.
namespace CLI { class App; }

namespace vdrive::cli {
void add_demo_command(CLI::App& app);
}
