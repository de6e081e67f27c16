#pragma once
// `vdrive esi --drive ID [-o FILE] [--without-od] [--eeprom-image] [--profile-dir DIR]`: writes the
// product's EtherCAT Slave Information XML (see vdrive/esi/esi_export.hpp, docs/esi.md) to FILE,
// or to stdout.
namespace CLI { class App; }

namespace vdrive::cli {
void add_esi_command(CLI::App& app);
}
