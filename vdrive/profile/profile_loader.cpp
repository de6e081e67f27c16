#include "vdrive/profile/profile_loader.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "vdrive/profile/embedded_profiles.hpp"
#include "vdrive/profile/profile_sections.hpp"
#include "vdrive/profile/profile_text.hpp"
#include "vdrive/profile/yaml_map_reader.hpp"

namespace vdrive::profile {
namespace {

// CoE data type names accepted in PDO entries and their ETG.1000.6 codes.
struct DataTypeName {
  std::string_view name;
  std::uint8_t code;
  std::uint8_t bits;
};
constexpr DataTypeName kDataTypes[] = {
    {"BOOLEAN", 0x01, 1},    {"INTEGER8", 0x02, 8},    {"INTEGER16", 0x03, 16},
    {"INTEGER32", 0x04, 32}, {"UNSIGNED8", 0x05, 8},   {"UNSIGNED16", 0x06, 16},
    {"UNSIGNED32", 0x07, 32}, {"INTEGER64", 0x15, 64}, {"UNSIGNED64", 0x1B, 64},
};

std::string known_list() {
  std::string s;
  for (const auto& id : known_products()) s += (s.empty() ? "" : ", ") + id;
  return s;
}

Identity read_identity(YamlMapReader m) {
  Identity id;
  id.vendor_id = m.u32("vendor_id");
  id.product_code = m.u32("product_code");
  id.revision = m.u32("revision");
  id.serial = m.u32("serial");
  id.device_type = m.u32("device_type");
  id.device_name = m.string("device_name");
  id.hardware_version = m.string("hardware_version");
  id.software_version = m.string("software_version");
  id.vendor_name = m.string("vendor_name");
  id.order_code = m.string("order_code");
  id.group = m.string("group");
  if (m.has("product_code_mask")) id.product_code_mask = m.u32("product_code_mask");
  m.finish();
  return id;
}

EscResources read_esc(YamlMapReader m) {
  EscResources e;
  e.type = m.u8("type");
  e.revision = m.u8("revision");
  e.build = m.u16("build");
  e.fmmu_count = m.u8("fmmu_count");
  e.sm_count = m.u8("sm_count");
  e.ram_kib = m.u8("ram_kib");
  e.port_descriptor = m.u8("port_descriptor");
  e.features = m.u16("features");
  e.eeprom_bytes = m.u16("eeprom_bytes");
  // SII word 0x3E holds the size as (kbit - 1): 1 kbit (128 bytes) steps, at most 64 kbit here.
  if (e.eeprom_bytes < 256 || e.eeprom_bytes % 128 != 0)
    m.fail("eeprom_bytes", "expected a multiple of 128 bytes, at least 256");
  if (e.fmmu_count == 0 || e.fmmu_count > 16) m.fail("fmmu_count", "expected 1..16");
  if (e.sm_count == 0 || e.sm_count > 16) m.fail("sm_count", "expected 1..16");
  e.pdi_control = m.u16("pdi_control");
  e.pdi_config = m.u16("pdi_config");
  e.sync_pulse_length = m.u16("sync_pulse_length");
  e.extended_pdi_config = m.u16("extended_pdi_config");
  e.station_alias = m.u16("station_alias");
  m.finish();
  return e;
}

Mailbox read_mailbox(YamlMapReader m) {
  Mailbox mb;
  mb.rx_offset = m.u16("rx_offset");
  mb.rx_size = m.u16("rx_size");
  mb.tx_offset = m.u16("tx_offset");
  mb.tx_size = m.u16("tx_size");
  const char* boot_keys[] = {"boot_rx_offset", "boot_rx_size", "boot_tx_offset", "boot_tx_size"};
  const int present = static_cast<int>(std::count_if(
      std::begin(boot_keys), std::end(boot_keys), [&](const char* k) { return m.has(k); }));
  if (present != 0 && present != 4)
    m.fail({}, "boot_rx_offset, boot_rx_size, boot_tx_offset, boot_tx_size: give all four or none");
  if (present == 4) {
    mb.boot_rx_offset = m.u16("boot_rx_offset");
    mb.boot_rx_size = m.u16("boot_rx_size");
    mb.boot_tx_offset = m.u16("boot_tx_offset");
    mb.boot_tx_size = m.u16("boot_tx_size");
  }
  mb.protocols = m.u16("protocols");
  m.finish();
  return mb;
}

MailboxSmRules read_rules(YamlMapReader m) {
  MailboxSmRules r;
  r.sm0_min_length = m.u16("sm0_min_length");
  r.sm0_max_length = m.u16("sm0_max_length");
  r.sm1_min_length = m.u16("sm1_min_length");
  r.sm1_max_length = m.u16("sm1_max_length");
  r.sm0_start_min = m.u16("sm0_start_min");
  r.sm0_start_max = m.u16("sm0_start_max");
  r.sm1_start_min = m.u16("sm1_start_min");
  r.sm1_start_max = m.u16("sm1_start_max");
  r.sm0_control_mask = m.u8("sm0_control_mask");
  r.sm0_control_value = m.u8("sm0_control_value");
  r.sm1_control_mask = m.u8("sm1_control_mask");
  r.sm1_control_value = m.u8("sm1_control_value");
  r.require_even_start = m.boolean("require_even_start");
  r.require_even_sm1_start = m.has("require_even_sm1_start") ? m.boolean("require_even_sm1_start") : r.require_even_start;
  m.finish();
  return r;
}

SyncManagerSpec::Kind read_kind(YamlMapReader& m) {
  const std::string k = m.string("kind");
  if (k == "mailbox_out") return SyncManagerSpec::Kind::MailboxOut;
  if (k == "mailbox_in") return SyncManagerSpec::Kind::MailboxIn;
  if (k == "outputs") return SyncManagerSpec::Kind::Outputs;
  if (k == "inputs") return SyncManagerSpec::Kind::Inputs;
  m.fail("kind", "expected one of mailbox_out, mailbox_in, outputs, inputs");
}

std::vector<SyncManagerSpec> read_sync_managers(YamlMapReader& root, std::uint8_t sm_count) {
  const YAML::Node seq = root.sequence("sync_managers");
  if (seq.size() > sm_count)
    root.fail("sync_managers", "lists " + std::to_string(seq.size()) + " SyncManagers, esc.sm_count is " +
                                   std::to_string(sm_count));
  std::vector<SyncManagerSpec> out;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader m = root.element(seq, "sync_managers", i);
    SyncManagerSpec sm;
    sm.kind = read_kind(m);
    sm.start = m.u16("start");
    sm.length = m.u16("length");
    sm.control = m.u8("control");
    sm.enable = m.boolean("enable");
    m.finish();
    out.push_back(sm);
  }
  return out;
}

AlStatusCodes read_al_codes(YamlMapReader m) {
  AlStatusCodes c;
  c.invalid_transition = m.u16("invalid_transition");
  c.unknown_state = m.u16("unknown_state");
  c.bootstrap_not_supported = m.u16("bootstrap_not_supported");
  c.invalid_mailbox_config = m.u16("invalid_mailbox_config");
  c.invalid_boot_mailbox_config = m.u16("invalid_boot_mailbox_config");
  c.sync_watchdog = m.u16("sync_watchdog");
  c.invalid_output_config = m.u16("invalid_output_config");
  c.invalid_input_config = m.u16("invalid_input_config");
  c.invalid_watchdog_config = m.u16("invalid_watchdog_config");
  c.invalid_input_mapping = m.u16("invalid_input_mapping");
  c.invalid_output_mapping = m.u16("invalid_output_mapping");
  c.sync_mode_not_supported = m.u16("sync_mode_not_supported");
  c.sync_error = m.u16("sync_error");
  c.no_sync_error = m.u16("no_sync_error");
  c.invalid_dc_sync_config = m.u16("invalid_dc_sync_config");
  c.pll_error = m.u16("pll_error");
  c.invalid_sync_cycle_time = m.u16("invalid_sync_cycle_time");
  c.eeprom_error = m.u16("eeprom_error");
  m.finish();
  return c;
}

SiiCheck read_sii_check(YamlMapReader m) {
  SiiCheck c;
  c.enabled = true;
  c.error_bits = m.u16("error_bits");
  if ((c.error_bits & ~0x7800u) != 0) m.fail("error_bits", "expected 0x0502 error bits 11-14 only (mask 0x7800)");
  c.identity = m.boolean("identity");
  c.every_state = m.boolean("every_state");
  c.clearable = m.boolean("clearable");
  m.finish();
  return c;
}

PdoEntrySpec read_pdo_entry(YamlMapReader m) {
  PdoEntrySpec e;
  e.index = m.u16("index");
  e.subindex = m.u8("subindex");
  e.bit_length = m.u8("bits");
  const std::string type = m.string("type");
  const auto* t = std::find_if(std::begin(kDataTypes), std::end(kDataTypes),
                               [&](const DataTypeName& d) { return d.name == type; });
  if (t == std::end(kDataTypes))
    m.fail("type", "expected a CoE type name (BOOLEAN, INTEGER8/16/32/64, UNSIGNED8/16/32/64)");
  if (t->bits != e.bit_length)
    m.fail("bits", type + " is " + std::to_string(t->bits) + " bits, not " + std::to_string(e.bit_length));
  e.data_type = t->code;
  e.name = m.string("name");
  m.finish();
  return e;
}

std::vector<PdoSpec> read_pdos(YamlMapReader& root, std::string_view key, std::uint16_t first_index) {
  std::vector<PdoSpec> out;
  if (!root.has(key)) return out;
  const YAML::Node seq = root.sequence(key);
  for (std::size_t i = 0; i < seq.size(); ++i) {
    YamlMapReader m = root.element(seq, key, i);
    PdoSpec pdo;
    pdo.index = m.u16("index");
    if (pdo.index < first_index || pdo.index > first_index + 0x1FF)
      m.fail("index", fmt::format("expected a mapping object index in 0x{:04X}..0x{:04X}", first_index,
                                  first_index + 0x1FF));
    pdo.name = m.string("name");
    pdo.sync_manager = m.u8("sync_manager");
    if (m.has("fixed")) pdo.fixed = m.boolean("fixed");
    const YAML::Node entries = m.sequence("entries");
    for (std::size_t j = 0; j < entries.size(); ++j)
      pdo.entries.push_back(read_pdo_entry(m.element(entries, "entries", j)));
    if (pdo.entries.size() > 255) m.fail("entries", "expected at most 255 entries");
    m.finish();
    out.push_back(std::move(pdo));
  }
  return out;
}

ProductProfile parse_profile(std::string_view id, const std::string& text, const std::string& file) {
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw_at(file, e.mark, "YAML syntax error: " + e.msg);
  }
  YamlMapReader root(doc, file, "");
  ProductProfile p;
  p.id = root.string("id");
  if (p.id != id) root.fail("id", "is '" + p.id + "', expected '" + std::string(id) + "' (the directory name)");
  p.title = root.string("title");
  p.identity = read_identity(root.map("identity"));
  p.esc = read_esc(root.map("esc"));
  p.mailbox = read_mailbox(root.map("mailbox"));
  p.mailbox_rules = read_rules(root.map("mailbox_rules"));
  p.sync_managers = read_sync_managers(root, p.esc.sm_count);
  p.has_bootstrap = root.boolean("has_bootstrap");
  if (p.has_bootstrap && !p.mailbox.boot_rx_offset)
    root.fail("has_bootstrap", "is true but mailbox has no boot_* mailbox");
  p.explicit_device_id = root.boolean("explicit_device_id");
  p.al_codes = read_al_codes(root.map("al_codes"));
  if (root.has("sii_check")) p.sii_check = read_sii_check(root.map("sii_check"));
  p.coe_details = root.u8("coe_details");
  p.complete_access_abort = root.u32("complete_access_abort");
  if (p.complete_access_abort < 0x05000000 || p.complete_access_abort > 0x08FFFFFF)
    root.fail("complete_access_abort", "expected an SDO abort code (0x05xxxxxx-0x08xxxxxx)");
  p.foe_details = root.u8("foe_details");
  if (root.has("foe_strict_firmware_check")) p.foe_strict_firmware_check = root.boolean("foe_strict_firmware_check");
  p.rx_pdos = read_pdos(root, "rx_pdos", 0x1600);
  p.tx_pdos = read_pdos(root, "tx_pdos", 0x1A00);
  p.sync = read_sync(root.map("sync"));
  p.pdo_rules = read_pdo_rules(root.map("pdo_rules"));
  p.modes = read_modes(root.map("modes"));
  p.homing = read_homing(root.map("homing"));
  p.touch_probe = read_touch_probe(root.map("touch_probe"));
  p.drive = read_drive(root.map("drive"), p.modes);
  check_consistency(p, root);
  root.finish();
  return p;
}

// The file beside profile.yaml: alarms.yaml or motors.yaml. Every product has both.
std::string read_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ProfileError(file + ": cannot read (every product has profile.yaml, alarms.yaml and motors.yaml)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void add_tables(ProductProfile& p, std::string_view alarms, std::string_view motors, const std::string& dir) {
  const std::string alarms_file = dir + "/alarms.yaml", motors_file = dir + "/motors.yaml";
  if (alarms.empty()) throw ProfileError(alarms_file + ": missing (every product has an alarm table)");
  if (motors.empty()) throw ProfileError(motors_file + ": missing (every product has a motor catalogue)");
  p.alarms = parse_alarms(p.id, std::string(alarms), alarms_file);
  p.motors = parse_motors(p.id, std::string(motors), motors_file);
  check_drive_alarms(p, dir + "/profile.yaml");
}

}  // namespace

std::vector<std::string> known_products() {
  std::vector<std::string> ids;
  for (const auto& e : embedded_profiles()) ids.emplace_back(e.id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

ProductProfile parse_profile_text(std::string_view id, const std::string& profile_yaml, std::string_view alarms_yaml,
                                  std::string_view motors_yaml, const std::string& dir) {
  ProductProfile p = parse_profile(id, profile_yaml, dir + "/profile.yaml");
  add_tables(p, alarms_yaml, motors_yaml, dir);
  return p;
}

ProductProfile load_profile(std::string_view id, const std::string& profile_dir) {
  if (profile_dir.empty()) {
    for (const auto& e : embedded_profiles()) {
      if (e.id != id) continue;
      const std::string dir = "profiles/" + std::string(id);
      ProductProfile p = parse_profile(id, std::string(e.yaml), dir + "/profile.yaml");
      add_tables(p, e.alarms_yaml, e.motors_yaml, dir);
      return p;
    }
    throw ProfileError("unknown product '" + std::string(id) + "' (known products: " + known_list() + ")");
  }
  // The id becomes a path component: refuse anything that could leave profile_dir.
  const bool plain = !id.empty() && std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
  if (!plain)
    throw ProfileError("unknown product '" + std::string(id) + "' (known products: " + known_list() + ")");
  const std::string file = profile_dir + "/" + std::string(id) + "/profile.yaml";
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw ProfileError("unknown product '" + std::string(id) + "': cannot read " + file +
                       " (built-in products: " + known_list() + ")");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string dir = profile_dir + "/" + std::string(id);
  ProductProfile p = parse_profile(id, text.str(), file);
  add_tables(p, read_file(dir + "/alarms.yaml"), read_file(dir + "/motors.yaml"), dir);
  return p;
}

}  // namespace vdrive::profile
