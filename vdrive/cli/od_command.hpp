#pragma once
// `vdrive od --drive ID [--index N] [--json]`: a product's object dictionary as the drive holds it
// (objects.yaml plus the identity from profile.yaml), one line (or JSON object) per entry: index,
// subindex, name, type, access, PDO mappability, default, range, units.
namespace CLI { class App; }

namespace vdrive::cli {
void add_od_command(CLI::App& app);
}
