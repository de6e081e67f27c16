#include "vdrive/cli/esi_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/output_file.hpp"
#include "vdrive/cli/product_source.hpp"
#include "vdrive/esi/esi_export.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::cli {
namespace {

struct EsiCommandOptions {
  std::string drive;
  std::string output;        // empty or "-": stdout
  std::string profile_dir;
  bool without_od = false;
  bool eeprom_image = false;
};

void run(const EsiCommandOptions& o) {
  const ProductSource source = load_product_source(o.drive, o.profile_dir);
  const profile::ProductProfile& p = source.profile;
  const std::shared_ptr<const od::Dictionary> dict = source.dictionary;
  esi::EsiOptions options;
  options.with_dictionary = !o.without_od;
  options.eeprom_image = o.eeprom_image;
  const std::string xml = esi::export_esi(p, *dict, options);
  if (o.output.empty() || o.output == "-") {
    std::fwrite(xml.data(), 1, xml.size(), stdout);
  } else {
    write_output_file(o.output, xml);
  }
}

}  // namespace

void add_esi_command(CLI::App& app) {
  auto o = std::make_shared<EsiCommandOptions>();
  CLI::App* cmd = app.add_subcommand("esi", "Write a product's EtherCAT Slave Information (ESI) XML file");
  cmd->add_option("--drive,-d", o->drive, "Product (see list-drives)")->required();
  cmd->add_option("--output,-o", o->output, "Output file (default: stdout)");
  cmd->add_flag("--without-od", o->without_od, "Leave the object dictionary out (the minimal ESI variant)");
  cmd->add_flag("--eeprom-image", o->eeprom_image, "Put the whole SII image in <Eeprom><Data>");
  cmd->add_option("--profile-dir", o->profile_dir, "Load products from DIR/<id>/ instead of the built-in ones");
  cmd->callback([o] { run(*o); });
}

}  // namespace vdrive::cli
