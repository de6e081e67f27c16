#pragma once
// `vdrive sii --drive ID (-o FILE | --hex)`: a product's SII EEPROM image, as the drive's ESC
// loads it, written as a binary file (for eepromtool, siitool) or as a hex dump on stdout.
namespace CLI { class App; }

namespace vdrive::cli {
void add_sii_command(CLI::App& app);
}
