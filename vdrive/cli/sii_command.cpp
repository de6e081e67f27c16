#include "vdrive/cli/sii_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/output_file.hpp"
#include "vdrive/cli/product_source.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::cli {
namespace {

struct SiiCommandOptions {
  std::string drive;
  std::string output;
  std::string profile_dir;
  bool hex = false;
};

// 16 bytes a line, each line starting with its SII word address (the unit EEPROM tools and
// ETG.1000.6 use): "0008: 6f 06 00 00 ...".
void print_hex(const std::vector<std::uint8_t>& bytes) {
  for (std::size_t at = 0; at < bytes.size(); at += 16) {
    const std::size_t n = std::min<std::size_t>(16, bytes.size() - at);
    fmt::print("{:04x}: {:02x}\n", at / 2,
               fmt::join(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                         bytes.begin() + static_cast<std::ptrdiff_t>(at + n), " "));
  }
}

void run(const SiiCommandOptions& o) {
  if (o.output.empty() == !o.hex)
    throw CliError(kExitBadArguments, "give either -o FILE (binary image) or --hex (hex dump on stdout)");
  const std::vector<std::uint8_t> image = load_product_source(o.drive, o.profile_dir).sii_image;
  if (o.hex) print_hex(image);
  else write_output_file(o.output, image);
}

}  // namespace

void add_sii_command(CLI::App& app) {
  auto o = std::make_shared<SiiCommandOptions>();
  CLI::App* cmd = app.add_subcommand("sii", "Write a product's SII EEPROM image (binary file or hex dump)");
  cmd->add_option("--drive,-d", o->drive, "Product (see list-drives)")->required();
  cmd->add_option("--output,-o", o->output, "Binary image file");
  cmd->add_flag("--hex", o->hex, "Hex dump on stdout instead, 16 bytes a line, with the word address");
  cmd->add_option("--profile-dir", o->profile_dir, "Load products from DIR/<id>/ instead of the built-in ones");
  cmd->callback([o] { run(*o); });
}

}  // namespace vdrive::cli
