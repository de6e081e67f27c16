#include "vdrive/esi/esi_import.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <map>
#include <mutex>

#include "ethercat/little_endian.hpp"
#include "ethercat/sii.hpp"
#include "vdrive/esi/eni_slave_device.hpp"
#include "vdrive/esi/esi_dictionary_reader.hpp"
#include "vdrive/esi/esi_error.hpp"
#include "vdrive/esi/esi_pdo_objects.hpp"
#include "vdrive/esi/esi_reader.hpp"
#include "vdrive/esi/generic_cia402.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::esi {
namespace {

using profile::ProductProfile;
using profile::SyncManagerSpec;

// Device@Physics letters -> register 0x0007, two bits per port: Y (MII) 11b, K (EBUS) 10b, else 00b.
std::uint8_t port_descriptor(const std::string& physics) {
  if (physics.empty()) return 0x0F;  // ETG default: two MII ports
  std::uint8_t d = 0;
  for (std::size_t p = 0; p < std::min<std::size_t>(4, physics.size()); ++p) {
    const char c = physics[p];
    const unsigned kind = c == 'Y' || c == 'H' ? 0x3 : c == 'K' ? 0x2 : 0x0;
    d = static_cast<std::uint8_t>(d | (kind << (2 * p)));
  }
  return d;
}

SyncManagerSpec::Kind sm_kind(const std::string& text) {
  if (text == "MBoxOut") return SyncManagerSpec::Kind::MailboxOut;
  if (text == "MBoxIn") return SyncManagerSpec::Kind::MailboxIn;
  if (text == "Outputs") return SyncManagerSpec::Kind::Outputs;
  return SyncManagerSpec::Kind::Inputs;
}

void esc_and_mailbox(const EsiDevice& d, ProductProfile& p) {
  p.esc.port_descriptor = port_descriptor(d.physics);
  // The ESC has at least three FMMUs (ET1200); the SII lists the ones the device uses.
  p.esc.fmmu_count = static_cast<std::uint8_t>(std::clamp<std::size_t>(d.fmmus.size(), 3, 16));
  const bool standard_order = d.fmmus.size() == 3 && d.fmmus[0] == "Outputs" && d.fmmus[1] == "Inputs" &&
                              d.fmmus[2] == "MBoxState";
  if (!standard_order)
    for (const std::string& f : d.fmmus)
      p.fmmu_usage.push_back(f == "Outputs" ? ecat::sii::fmmu_usage::kOutputs
                             : f == "Inputs" ? ecat::sii::fmmu_usage::kInputs
                             : f == "MBoxState" ? ecat::sii::fmmu_usage::kMailboxState
                                                : ecat::sii::fmmu_usage::kUnused);
  p.esc.sm_count = static_cast<std::uint8_t>(std::max<std::size_t>(4, std::min<std::size_t>(d.sync_managers.size(), 16)));
  // ConfigData: SII words 0-4 (PDI control, PDI configuration, SYNC pulse, extended PDI, alias).
  const std::vector<std::uint8_t>& c = d.config_data;
  auto word = [&](std::size_t w, std::uint16_t otherwise) {
    return c.size() >= 2 * w + 2 ? ecat::get_le16(c, 2 * w) : otherwise;
  };
  p.esc.pdi_control = word(0, p.esc.pdi_control);
  p.esc.pdi_config = word(1, p.esc.pdi_config);
  p.esc.sync_pulse_length = word(2, p.esc.sync_pulse_length);
  p.esc.extended_pdi_config = word(3, p.esc.extended_pdi_config);
  p.esc.station_alias = word(4, p.esc.station_alias);
  if (d.eeprom_bytes) p.esc.eeprom_bytes = static_cast<std::uint16_t>(std::min<std::uint32_t>(*d.eeprom_bytes, 0xFFFF));

  // No mailbox SyncManager, no mailbox: the SII mailbox words stay 0.
  p.mailbox.rx_offset = p.mailbox.rx_size = p.mailbox.tx_offset = p.mailbox.tx_size = 0;
  for (const EsiSyncManager& sm : d.sync_managers) {
    SyncManagerSpec s;
    s.kind = sm_kind(sm.kind);
    s.start = sm.start;
    s.length = sm.default_size;
    s.control = sm.control;
    s.enable = sm.enable;
    p.sync_managers.push_back(s);
    if (s.kind == SyncManagerSpec::Kind::MailboxOut) {
      p.mailbox.rx_offset = sm.start;
      p.mailbox.rx_size = sm.default_size;
      if (sm.min_size != 0) p.mailbox_rules.sm0_min_length = sm.min_size;
      if (sm.max_size != 0) p.mailbox_rules.sm0_max_length = sm.max_size;
    } else if (s.kind == SyncManagerSpec::Kind::MailboxIn) {
      p.mailbox.tx_offset = sm.start;
      p.mailbox.tx_size = sm.default_size;
      if (sm.min_size != 0) p.mailbox_rules.sm1_min_length = sm.min_size;
      if (sm.max_size != 0) p.mailbox_rules.sm1_max_length = sm.max_size;
    } else if (s.kind == SyncManagerSpec::Kind::Outputs) {
      p.pdo_rules.max_rx_bytes = sm.max_size != 0 ? sm.max_size : 0xFFFF;
    } else {
      p.pdo_rules.max_tx_bytes = sm.max_size != 0 ? sm.max_size : 0xFFFF;
    }
  }
  namespace proto = ecat::sii::mailbox_protocol;
  std::uint16_t protocols = 0;
  if (d.aoe) protocols |= proto::kAoE;
  if (d.eoe) protocols |= proto::kEoE;
  if (d.coe) protocols |= proto::kCoE;
  if (d.foe) protocols |= proto::kFoE;
  if (d.soe) protocols |= proto::kSoE;
  if (d.voe) protocols |= proto::kVoE;
  p.mailbox.protocols = protocols;
  if (d.boot_strap.size() == 8) {
    p.has_bootstrap = true;
    p.mailbox.boot_rx_offset = ecat::get_le16(d.boot_strap, 0);
    p.mailbox.boot_rx_size = ecat::get_le16(d.boot_strap, 2);
    p.mailbox.boot_tx_offset = ecat::get_le16(d.boot_strap, 4);
    p.mailbox.boot_tx_size = ecat::get_le16(d.boot_strap, 6);
  }
  p.coe_details = static_cast<std::uint8_t>((d.coe ? 0x01 : 0) | (d.sdo_info ? 0x02 : 0) | (d.pdo_assign ? 0x04 : 0) |
                                            (d.pdo_config ? 0x08 : 0) | (d.pdo_upload ? 0x10 : 0) |
                                            (d.complete_access ? 0x20 : 0));
  p.foe_details = d.foe ? 1 : 0;
  p.explicit_device_id = d.explicit_device_id;
}

// A PDO of the file: its default assignment (Sm) makes it part of the SII's PDO categories.
profile::PdoSpec pdo_spec(const EsiPdo& pdo, const std::vector<od::ObjectDesc>& objects) {
  profile::PdoSpec s;
  s.index = pdo.index;
  s.name = pdo.name;
  s.sync_manager = pdo.sm ? *pdo.sm : 0xFF;
  s.fixed = pdo.fixed;
  for (const EsiPdoEntry& e : pdo.entries) {
    profile::PdoEntrySpec entry;
    entry.index = e.index;
    entry.subindex = e.subindex;
    entry.bit_length = static_cast<std::uint8_t>(e.bit_length);
    entry.name = e.name;
    entry.data_type = coe_code(e.data_type);
    if (entry.data_type == 0 && e.index != 0)
      if (const od::EntryDesc* target = find_entry(objects, e.index, e.subindex))
        entry.data_type = static_cast<std::uint8_t>(target->type);
    s.entries.push_back(std::move(entry));
  }
  return s;
}

void pdos(const EsiDevice& d, ProductProfile& p) {
  auto rules = [&](const std::vector<EsiPdo>& list, std::vector<profile::PdoObjectRule>& out) {
    for (const EsiPdo& pdo : list) {
      profile::PdoObjectRule r;
      r.index = pdo.index;
      r.fixed = pdo.fixed;
      const od::EntryDesc* count = find_entry(d.objects, pdo.index, 0);
      std::size_t entries = pdo.entries.size();
      if (const od::ObjectDesc* o = find_object(d.objects, pdo.index))
        entries = std::max<std::size_t>(entries, o->max_subindex());
      if (count != nullptr && count->max) entries = std::max<std::size_t>(entries, static_cast<std::size_t>(*count->max));
      r.max_entries = static_cast<std::uint8_t>(std::min<std::size_t>(entries, 255));
      r.mandatory = pdo.mandatory;
      r.excludes = pdo.exclude;
      out.push_back(r);
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
  };
  rules(d.rx_pdos, p.pdo_rules.rx_objects);
  rules(d.tx_pdos, p.pdo_rules.tx_objects);
  for (const EsiPdo& pdo : d.rx_pdos)
    if (pdo.sm) p.rx_pdos.push_back(pdo_spec(pdo, d.objects));
  for (const EsiPdo& pdo : d.tx_pdos)
    if (pdo.sm) p.tx_pdos.push_back(pdo_spec(pdo, d.objects));
  // How many PDOs 1C12h/1C13h take: their subindexes, else every PDO of the file.
  auto assignable = [&](std::uint16_t index, std::size_t pdo_count) {
    const od::ObjectDesc* o = find_object(d.objects, index);
    const std::size_t n = o != nullptr ? std::max<std::size_t>(o->max_subindex(), 1) : pdo_count;
    return static_cast<std::uint8_t>(std::min<std::size_t>(n, 255));
  };
  p.pdo_rules.max_rx_assigned = assignable(0x1C12, d.rx_pdos.size());
  p.pdo_rules.max_tx_assigned = assignable(0x1C13, d.tx_pdos.size());
  auto writable = [&](std::uint16_t index, std::uint8_t sub) {
    const od::EntryDesc* e = find_entry(d.objects, index, sub);
    return e != nullptr && (e->access & od::access::kWriteAll) != 0;
  };
  p.pdo_rules.assign_writable = d.pdo_assign || writable(0x1C12, 1) || writable(0x1C13, 1);
  const bool any_free = std::any_of(d.rx_pdos.begin(), d.rx_pdos.end(), [](const EsiPdo& x) { return !x.fixed; }) ||
                        std::any_of(d.tx_pdos.begin(), d.tx_pdos.end(), [](const EsiPdo& x) { return !x.fixed; });
  p.pdo_rules.mapping_writable = any_free;
  // ETG.1000.6: PDO assignment and mapping change in PreOp; sizes are checked at PreOp->SafeOp.
  p.pdo_rules.writable_states = profile::kStatePreOp;
  p.pdo_rules.wrong_state_abort = 0x08000022;
}

// 1C32h (SM2) or 1C33h (SM3) as the dictionary gives it; every sync type the op modes allow.
profile::SyncObjectSpec sync_object(const std::vector<od::ObjectDesc>& o, std::uint16_t index, bool outputs,
                                    const profile::SyncSpec& s) {
  profile::SyncObjectSpec x;
  x.default_sync_type = static_cast<std::uint16_t>(default_of(o, index, 1, 0));
  x.accepted_sync_types = {0x00, outputs ? std::uint16_t{0x01} : std::uint16_t{0x22}};
  if (!outputs) x.accepted_sync_types.push_back(0x01);
  if (s.dc_sync0) x.accepted_sync_types.push_back(0x02);
  if (s.dc_sync1) x.accepted_sync_types.push_back(0x03);
  if (std::find(x.accepted_sync_types.begin(), x.accepted_sync_types.end(), x.default_sync_type) ==
      x.accepted_sync_types.end())
    x.accepted_sync_types.push_back(x.default_sync_type);
  x.default_cycle_time_ns = static_cast<std::uint32_t>(default_of(o, index, 2, 0));
  const od::EntryDesc* cycle = find_entry(o, index, 2);
  x.cycle_time_writable = cycle == nullptr || (cycle->access & od::access::kWriteAll) != 0;
  x.default_shift_time_ns = static_cast<std::uint32_t>(default_of(o, index, 3, 0));
  const od::EntryDesc* shift = find_entry(o, index, 3);
  x.shift_time_writable = shift != nullptr && (shift->access & od::access::kWriteAll) != 0;
  x.supported_sync_types = static_cast<std::uint16_t>(default_of(o, index, 4, 0));
  x.min_cycle_time_ns = static_cast<std::uint32_t>(default_of(o, index, 5, 0));
  x.calc_and_copy_time_ns = static_cast<std::uint32_t>(default_of(o, index, 6, 0));
  x.delay_time_ns = static_cast<std::uint32_t>(default_of(o, index, 9, 0));
  x.error_counters = find_entry(o, index, 0x0B) != nullptr || find_entry(o, index, 0x0C) != nullptr;
  return x;
}

void synchronisation(const EsiDevice& d, ProductProfile& p) {
  profile::SyncSpec& s = p.sync;
  // Free run and SM-synchronous always (ETG.1020: every device can run without DC); DC modes as
  // <Dc><OpMode> AssignActivate declares them (0x0981 bit 1 SYNC0, bit 2 SYNC1).
  s.free_run = true;
  s.sm2_event = true;
  s.accepted_dc_activation = {0x00};
  for (const EsiOpMode& m : d.op_modes) {
    const auto activation = static_cast<std::uint8_t>(m.assign_activate >> 8);
    if (activation & 0x02) s.dc_sync0 = true;
    if (activation & 0x04) s.dc_sync1 = true;
    if (activation != 0 && std::find(s.accepted_dc_activation.begin(), s.accepted_dc_activation.end(), activation) ==
                               s.accepted_dc_activation.end())
      s.accepted_dc_activation.push_back(activation);
  }
  // A device without DC op modes does not look at the DC activation (simple I/O has no firmware to
  // refuse it): any pattern is taken, and it keeps running on its own.
  if (d.op_modes.empty()) s.accepted_dc_activation = {0x00, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07};
  // Any cycle time from 1C32h-05h (minimum cycle time) up; 1 ns steps.
  s.cycle_times_ns.clear();
  s.cycle_step_ns = 1;
  s.cycle_min_ns = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(default_of(d.objects, 0x1C32, 5, 0)));
  s.cycle_max_ns = 0xFFFFFFFF;
  s.cycle_must_equal_sync0 = true;
  s.sm2 = sync_object(d.objects, 0x1C32, true, s);
  s.sm3 = sync_object(d.objects, 0x1C33, false, s);
  // Shift times: whatever the dictionary lets a master write, below the cycle.
  s.input_shift = {0, 0xFFFFFFFF, true, {}};
  s.output_shift = {0, 0xFFFFFFFF, true, {}};
  s.sm_event_missed_subindex = find_entry(d.objects, 0x1C32, 0x0B) ? 0x0B : 0;
  s.cycle_too_small_subindex = find_entry(d.objects, 0x1C32, 0x0C) ? 0x0C : 0;
  s.sync_error_flag = find_entry(d.objects, 0x1C32, 0x20) != nullptr;
  // An ESI device (ETG slave stack) takes SM2 events as they come: no lock onto the SM2 cycle.
  s.sm2_in_step_check = false;
}

std::string visible_default(const std::vector<od::ObjectDesc>& objects, std::uint16_t index) {
  const od::EntryDesc* e = find_entry(objects, index, 0);
  if (e == nullptr || e->type != od::DataType::VisibleString) return {};
  std::string s(e->default_value.begin(), e->default_value.end());
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

// The SII image: the file's own, padded to its EEPROM size with 0xFF (erased), or built from the
// profile; without a ByteSize the EEPROM is 2 KiB, or larger where the image needs it.
std::vector<std::uint8_t> sii_image(const EsiDevice& d, ProductProfile& p) {
  if (!d.eeprom_data.empty()) {
    std::vector<std::uint8_t> image = d.eeprom_data;
    if (image.size() < p.esc.eeprom_bytes) image.resize(p.esc.eeprom_bytes, 0xFF);
    p.esc.eeprom_bytes = static_cast<std::uint16_t>(std::min<std::size_t>(image.size(), 0xFFFF));
    return image;
  }
  for (;;) {
    try {
      return profile::build_sii_image(p);
    } catch (const profile::ProfileError& e) {
      if (d.eeprom_bytes || p.esc.eeprom_bytes >= 0x8000)
        throw EsiError(fmt::format("{}:{}: <Device>: {}", d.file, d.line, e.what()));
      p.esc.eeprom_bytes = static_cast<std::uint16_t>(p.esc.eeprom_bytes * 2);
    }
  }
}

std::uint32_t parse_number(std::string_view text, std::string_view name, std::string_view what) {
  std::uint32_t v = 0;
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    text.remove_prefix(2);
    base = 16;
  } else if (text.size() > 2 && text[0] == '#' && (text[1] == 'x' || text[1] == 'X')) {
    text.remove_prefix(2);
    base = 16;
  }
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v, base);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw EsiError(fmt::format("'{}': the {} '{}' is not a number (decimal or 0x hex, at most 32 bits)", name, what, text));
  return v;
}

std::string describe(const EsiDevice& d) {
  return fmt::format("{} (product code 0x{:08X}, revision 0x{:08X}, line {})", d.type_text.empty() ? d.name : d.type_text,
                     d.product_code, d.revision, d.line);
}

// The file's own PDOs are what the device maps: an entry they map is PDO-mappable in that direction,
// whatever the dictionary's PdoMapping says (vendors' files leave it out).
void make_pdo_entries_mappable(std::vector<od::ObjectDesc>& objects, const EsiDevice& d) {
  auto mark = [&](const std::vector<EsiPdo>& pdos, std::uint16_t bit) {
    for (const EsiPdo& pdo : pdos)
      for (const EsiPdoEntry& e : pdo.entries)
        for (od::ObjectDesc& o : objects)
          if (o.index == e.index)
            for (od::EntryDesc& x : o.entries)
              if (x.subindex == e.subindex) x.access = static_cast<std::uint16_t>(x.access | bit);
  };
  mark(d.rx_pdos, od::access::kRxPdoMappable);
  mark(d.tx_pdos, od::access::kTxPdoMappable);
}

// What a file says that no device can be: a PDO entry naming a PDO mapping or assignment object, a
// process-data SyncManager in the ESC's register area other than an output one on the digital
// output data (0F00h-0F03h, a digital output terminal's SM0).
void check_device(const EsiDevice& d) {
  for (const std::vector<EsiPdo>* list : {&d.rx_pdos, &d.tx_pdos})
    for (const EsiPdo& pdo : *list)
      for (const EsiPdoEntry& e : pdo.entries)
        if (e.index >= 0x1600 && e.index <= 0x1C13)
          throw EsiError(fmt::format("{}:{}: <Entry>: PDO {:04X}h maps {:04X}h:{:02X}h, a PDO mapping or assignment "
                                     "object, not data; the file is inconsistent", d.file, e.line, pdo.index, e.index,
                                     e.subindex));
  for (const EsiSyncManager& sm : d.sync_managers) {
    if ((sm.kind != "Outputs" && sm.kind != "Inputs") || sm.start >= 0x1000) continue;
    // 3-buffered: the ESC keeps three copies of the window.
    const bool on_output_data = sm.kind == "Outputs" && sm.start >= 0x0F00 && sm.start + 3u * sm.default_size <= 0x0F04;
    if (!on_output_data)
      throw EsiError(fmt::format("{}:{}: <Sm>: {} at {:04X}h, {} bytes, in the ESC's register area: a process-data "
                                 "SyncManager is in process RAM (1000h up), or for outputs on the digital output "
                                 "data (0F00h-0F03h, three buffers included); not served",
                                 d.file, sm.line, sm.kind, sm.start, sm.default_size));
  }
}

}  // namespace

ImportedDevice import_device(const EsiDevice& d) {
  check_device(d);
  ImportedDevice out;
  ProductProfile& p = out.profile;
  p.id = d.type_text.empty() ? d.name : d.type_text;
  p.title = d.name;
  p.identity.vendor_id = d.vendor_id;
  p.identity.product_code = d.product_code;
  p.identity.revision = d.revision;
  p.identity.device_type = static_cast<std::uint32_t>(
      default_of(d.objects, 0x1000, 0, d.profile_no | (static_cast<std::uint32_t>(d.add_info) << 16)));
  p.identity.device_name = d.name;
  p.identity.hardware_version = visible_default(d.objects, 0x1009);
  p.identity.software_version = visible_default(d.objects, 0x100A);
  p.identity.vendor_name = d.vendor_name;
  p.identity.order_code = d.type_text;
  p.identity.group = d.group_type;
  // Drives and I/O alike: nothing of the three products' own rules, only ETG behaviour.
  p.mailbox_rules.sm0_start_min = p.mailbox_rules.sm1_start_min = 0x1000;
  esc_and_mailbox(d, p);
  pdos(d, p);
  synchronisation(d, p);
  if (is_cia402_drive(d.profile_no, d.objects)) apply_generic_cia402(p, d.objects);
  // The file's own SII image also gives the unit's serial number (words 0Eh-0Fh), which 1018h-04h
  // then reports as the SII does.
  if (d.eeprom_data.size() >= 2 * ecat::sii::kWordSerial + 4)
    p.identity.serial = ecat::get_le32(d.eeprom_data, 2 * ecat::sii::kWordSerial);
  out.sii_image = sii_image(d, p);
  // PDO objects the file leaves without values get the default assignment and mapping of its PDOs,
  // as the device's firmware would have them (od/default_pdo_objects.hpp).
  std::vector<od::ObjectDesc> objects = d.objects;
  add_pdo_objects(objects, d);
  make_pdo_entries_mappable(objects, d);
  try {
    out.dictionary = std::make_shared<const od::Dictionary>(od::Dictionary::from_objects(std::move(objects), p));
  } catch (const EsiError&) {
    throw;
  } catch (const profile::ProfileError& e) {
    throw EsiError(fmt::format("{}:{}: <Device>: {}", d.file, d.line, e.what()));
  }
  return out;
}

bool is_esi_reference(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower.ends_with(".xml") || lower.find(".xml:") != std::string::npos || lower.find(".xml#") != std::string::npos;
}

DeviceReference parse_device_reference(std::string_view name) {
  DeviceReference r;
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::size_t xml = lower.rfind(".xml");
  const std::size_t end = xml == std::string::npos ? name.size() : xml + 4;
  r.path = std::string(name.substr(0, end));
  std::string_view rest = name.substr(end);
  if (rest.empty()) return r;
  rest.remove_prefix(1);  // ':'
  const std::size_t colon = rest.find(':');
  r.product_code = parse_number(rest.substr(0, colon), name, "product code");
  if (colon != std::string_view::npos) r.revision = parse_number(rest.substr(colon + 1), name, "revision");
  return r;
}

const EsiDevice& select_device(const std::vector<EsiDevice>& devices, const DeviceReference& r) {
  std::vector<const EsiDevice*> matches;
  for (const EsiDevice& d : devices)
    if ((!r.product_code || d.product_code == *r.product_code) && (!r.revision || d.revision == *r.revision))
      matches.push_back(&d);
  if (matches.size() == 1) return *matches.front();
  std::string list;
  for (const EsiDevice& d : devices) list += "\n  " + fmt::format("{}:0x{:08X}:0x{:08X}  {}", r.path, d.product_code, d.revision, describe(d));
  if (matches.empty())
    throw EsiError(fmt::format("{}: no device with product code {} and revision {}; the file has:{}", r.path,
                               r.product_code ? fmt::format("0x{:08X}", *r.product_code) : "(any)",
                               r.revision ? fmt::format("0x{:08X}", *r.revision) : "(any)", list));
  throw EsiError(fmt::format("{}: {} devices match; name one by product code and revision:{}", r.path, matches.size(), list));
}

std::shared_ptr<const ImportedDevice> load_esi_device(std::string_view name) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const ImportedDevice>, std::less<>> cache;
  const std::lock_guard lock(mutex);
  if (const auto it = cache.find(name); it != cache.end()) return it->second;
  std::shared_ptr<const ImportedDevice> imported;
  if (is_eni_slave_reference(name)) {
    imported = std::make_shared<const ImportedDevice>(import_device(load_eni_slave_device(name).device));
  } else {
    const DeviceReference r = parse_device_reference(name);
    const std::vector<EsiDevice> devices = read_esi_file(r.path);
    imported = std::make_shared<const ImportedDevice>(import_device(select_device(devices, r)));
  }
  cache.emplace(std::string(name), imported);
  return imported;
}

}  // namespace vdrive::esi
