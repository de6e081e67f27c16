#include "vdrive/cli/od_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <memory>
#include <optional>
#include <string>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/od/unit_text.hpp"
#include "vdrive/od/access_text.hpp"
#include "vdrive/od/entry_value.hpp"
#include "vdrive/cli/product_source.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::cli {
namespace {

struct OdCommandOptions {
  std::string drive;
  std::string index;         // text as given: 0x6040, 6040h or decimal
  std::string profile_dir;
  bool json = false;
};

std::uint16_t parse_index(const std::string& text) {
  std::string_view s = text;
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  } else if (!s.empty() && (s.back() == 'h' || s.back() == 'H')) {
    base = 16;
    s.remove_suffix(1);
  }
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value, base);
  if (s.empty() || ec != std::errc{} || end != s.data() + s.size() || value > 0xFFFF)
    throw CliError(kExitBadArguments, fmt::format("--index: '{}' is not an object index (0x0000-0xFFFF, e.g. 0x6040)", text));
  return static_cast<std::uint16_t>(value);
}

std::int64_t integer_value(const od::EntryDesc& e) { return od::entry_integer(e, e.default_value); }

std::string string_value(const od::EntryDesc& e) {
  const auto nul = std::find(e.default_value.begin(), e.default_value.end(), std::uint8_t{0});
  return std::string(e.default_value.begin(), nul);
}

std::string hex_bytes(const od::EntryDesc& e) {
  std::string out;
  for (const std::uint8_t b : e.default_value) out += fmt::format("{:02x}", b);
  return out;
}

std::string default_text(const od::EntryDesc& e) {
  if (e.type == od::DataType::VisibleString) return fmt::format("\"{}\"", string_value(e));
  if (e.type == od::DataType::OctetString) return hex_bytes(e);
  return std::to_string(integer_value(e));
}

std::string range_text(const od::EntryDesc& e) {
  if (!e.min && !e.max) return "-";
  return fmt::format("{}..{}", e.min ? std::to_string(*e.min) : std::string(),
                     e.max ? std::to_string(*e.max) : std::string());
}

void print_text(const std::vector<const od::EntryDesc*>& entries) {
  fmt::print("{:<6} {:<3} {:<40} {:<4} {:<16} {:<3} {:<22} {:<24} {:<28} {}\n", "INDEX", "SUB", "NAME", "TYPE",
             "ACCESS", "PDO", "DEFAULT", "RANGE", "UNITS", "UNITS (MANUAL)");
  for (const od::EntryDesc* e : entries) {
    const std::string english = e->units.empty() ? "-" : od::english_units(e->units);
    std::string line = fmt::format("{:04X}h  {:02X}h {:<40} {:<4} {:<16} {:<3} {:<22} {:<24} {:<28} {}", e->index, e->subindex,
                                   e->name, od::short_name(e->type), od::access_text(e->access), od::pdo_text(e->access),
                                   default_text(*e), range_text(*e), english,
                                   english == e->units || e->units.empty() ? "" : e->units);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    fmt::print("{}\n", line);
  }
}

void print_json(const std::string& product, const std::vector<const od::EntryDesc*>& entries) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const od::EntryDesc* e : entries) {
    nlohmann::ordered_json j;
    j["index"] = e->index;
    j["subindex"] = e->subindex;
    j["name"] = e->name;
    j["type"] = od::short_name(e->type);
    j["bit_length"] = e->bit_length;
    j["access"] = od::access_text(e->access);
    j["access_bits"] = e->access;
    j["pdo"] = od::pdo_text(e->access) == "-" ? nullptr : nlohmann::ordered_json(od::pdo_text(e->access));
    if (e->type == od::DataType::VisibleString) j["default"] = string_value(*e);
    else if (e->type == od::DataType::OctetString) j["default"] = hex_bytes(*e);
    else j["default"] = integer_value(*e);
    j["min"] = e->min ? nlohmann::ordered_json(*e->min) : nlohmann::ordered_json(nullptr);
    j["max"] = e->max ? nlohmann::ordered_json(*e->max) : nlohmann::ordered_json(nullptr);
    j["units"] = e->units.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(od::english_units(e->units));
    j["units_manual"] = e->units.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(e->units);
    j["synthesized"] = e->synthesized;
    j["manual_line"] = e->manual_line;
    list.push_back(std::move(j));
  }
  nlohmann::ordered_json out;
  out["product"] = product;
  out["entries"] = std::move(list);
  // Names come from the manuals and are UTF-8; anything else is replaced, never a crash.
  fmt::print("{}\n", out.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace));
}

void run(const OdCommandOptions& o) {
  const ProductSource source = load_product_source(o.drive, o.profile_dir);
  const std::optional<std::uint16_t> only =
      o.index.empty() ? std::nullopt : std::optional<std::uint16_t>(parse_index(o.index));
  const profile::ProductProfile& p = source.profile;
  const std::shared_ptr<const od::Dictionary> dict = source.dictionary;

  std::vector<const od::EntryDesc*> entries;
  for (const od::ObjectDesc& object : dict->objects()) {
    if (only && object.index != *only) continue;
    for (const od::EntryDesc& e : object.entries) entries.push_back(&e);
  }
  if (only && entries.empty())
    throw CliError(kExitBadArguments, fmt::format("--index: {} has no object {:04X}h", o.drive, *only));
  if (o.json) print_json(p.id, entries);
  else print_text(entries);
}

}  // namespace

void add_od_command(CLI::App& app) {
  auto o = std::make_shared<OdCommandOptions>();
  CLI::App* cmd = app.add_subcommand("od", "Print a product's object dictionary, one line per entry");
  cmd->add_option("--drive,-d", o->drive, "Product (see list-drives)")->required();
  cmd->add_option("--index", o->index, "Only this object (0x6040, 6040h or decimal)");
  cmd->add_flag("--json", o->json, "JSON instead of text");
  cmd->add_option("--profile-dir", o->profile_dir, "Load products from DIR/<id>/ instead of the built-in ones");
  cmd->callback([o] { run(*o); });
}

}  // namespace vdrive::cli
