#pragma once
// `vdrive list-drives`: the products this build knows, one per line: id and title.
namespace CLI { class App; }

namespace vdrive::cli {
void add_list_drives_command(CLI::App& app);
}
