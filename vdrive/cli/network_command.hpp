#pragma once
// `vdrive network --from-eni FILE [--esi-dir DIR]... [-o FILE]`: the network file (YAML) equivalent
// to a master's ENI, with a comment per slave saying how it was matched (built-in product, ESI
// device, nearest revision), so a user can review and edit the bench before serving it with
// `vdrive run --network`. A slave nothing matches: exit 2 naming it (vdrive/machine/eni_reader.hpp).
namespace CLI { class App; }

namespace vdrive::cli {
void add_network_command(CLI::App& app);
}
