#include "vdrive/esi/esi_export.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <optional>
#include <span>
#include <vector>

#include "ethercat/little_endian.hpp"
#include "ethercat/sii.hpp"
#include "vdrive/esi/esi_dictionary.hpp"
#include "vdrive/esi/esi_names.hpp"
#include "vdrive/esi/xml_writer.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::esi {
namespace {

using profile::PdoSpec;
using profile::ProductProfile;
using profile::SyncManagerSpec;

constexpr const char* kLcIdEnglish = "1033";

// Device@Physics: one letter per port from the ESC port descriptor (register 0x0007, 2 bits per
// port): MII 'Y', EBUS 'K', not implemented/configured ' '; trailing unused ports dropped.
std::string physics(std::uint8_t port_descriptor) {
  std::string s;
  for (int p = 0; p < 4; ++p) {
    const unsigned kind = (port_descriptor >> (2 * p)) & 0x3;
    s += kind == 0x3 ? 'Y' : kind == 0x2 ? 'K' : ' ';
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

const char* sm_text(SyncManagerSpec::Kind kind) {
  switch (kind) {
    case SyncManagerSpec::Kind::MailboxOut: return "MBoxOut";
    case SyncManagerSpec::Kind::MailboxIn: return "MBoxIn";
    case SyncManagerSpec::Kind::Outputs: return "Outputs";
    case SyncManagerSpec::Kind::Inputs: return "Inputs";
  }
  return "";
}

void write_sync_managers(XmlWriter& xml, const ProductProfile& p) {
  const profile::MailboxSmRules& r = p.mailbox_rules;
  for (const SyncManagerSpec& sm : p.sync_managers) {
    xml.open("Sm");
    using Kind = SyncManagerSpec::Kind;
    // Size limits the firmware enforces (mailbox: Err81.1-style checks; process data: PDO rules).
    std::uint32_t min = 0, max = 0;
    if (sm.kind == Kind::MailboxOut) min = r.sm0_min_length, max = r.sm0_max_length;
    if (sm.kind == Kind::MailboxIn) min = r.sm1_min_length, max = r.sm1_max_length;
    if (sm.kind == Kind::Outputs) max = p.pdo_rules.max_rx_bytes;
    if (sm.kind == Kind::Inputs) max = p.pdo_rules.max_tx_bytes;
    if (min != 0) xml.attr("MinSize", std::to_string(min));
    if (max != 0 && max != 0xFFFF) xml.attr("MaxSize", std::to_string(max));
    xml.attr("DefaultSize", std::to_string(sm.length));
    xml.attr("StartAddress", hex(sm.start, 4));
    xml.attr("ControlByte", hex(sm.control, 2));
    xml.attr("Enable", sm.enable ? "1" : "0");
    xml.close_with_text(sm_text(sm.kind));
  }
}

// Name and data type of a mapped object from the dictionary, when it knows the entry.
const od::EntryDesc* mapped_entry(const od::Dictionary& d, std::uint16_t index, std::uint8_t sub) {
  return index == 0 ? nullptr : d.find(index, sub);
}

void write_entry(XmlWriter& xml, std::uint16_t index, std::uint8_t sub, std::uint16_t bits,
                 const std::string& name, const std::string& type) {
  xml.open("Entry");
  xml.element("Index", hex(index, 4));
  if (index != 0) xml.element("SubIndex", std::to_string(sub));  // padding has none
  xml.element("BitLen", std::to_string(bits));
  if (!name.empty()) xml.element("Name", name);
  if (!type.empty()) xml.element("DataType", type);
  xml.close();
}

// A PDO of the default mapping, from the profile (the same data the SII PDO categories hold).
void write_default_pdo(XmlWriter& xml, const char* tag, const PdoSpec& pdo) {
  xml.open(tag);
  xml.attr("Fixed", pdo.fixed ? "1" : "0");
  if (pdo.sync_manager != 0xFF) xml.attr("Sm", std::to_string(pdo.sync_manager));
  xml.element("Index", hex(pdo.index, 4));
  xml.element("Name", pdo.name);
  for (const auto& e : pdo.entries)
    write_entry(xml, e.index, e.subindex, e.bit_length, e.name, type_name(e.data_type, e.bit_length));
  xml.close();
}

// A further mapping object the product has (PDO rules) but does not assign by default: no Sm
// attribute; its entries are the factory value of the mapping object in the dictionary, if any.
void write_optional_pdo(XmlWriter& xml, const char* tag, const profile::PdoObjectRule& rule,
                        const od::Dictionary& d, const char* fallback_name) {
  xml.open(tag);
  xml.attr("Fixed", rule.fixed ? "1" : "0");
  xml.element("Index", hex(rule.index, 4));
  const od::ObjectDesc* obj = d.find(rule.index);
  xml.element("Name", obj ? obj->name : fmt::format("{} {:04X}h", fallback_name, rule.index));
  const od::EntryDesc* count = d.find(rule.index, 0);
  const unsigned n = count && !count->default_value.empty() ? count->default_value[0] : 0;
  for (unsigned sub = 1; sub <= n; ++sub) {
    const od::EntryDesc* m = d.find(rule.index, static_cast<std::uint8_t>(sub));
    if (!m || m->default_value.size() < 4) break;
    const auto& v = m->default_value;  // little-endian: bit length, subindex, index
    const std::uint8_t bits = v[0], msub = v[1];
    const std::uint16_t midx = ecat::get_le16(v, 2);
    const od::EntryDesc* target = mapped_entry(d, midx, msub);
    write_entry(xml, midx, msub, bits, target ? target->name : std::string{},
                target ? type_name(target->type, target->bit_length) : std::string{});
  }
  xml.close();
}

void write_pdos(XmlWriter& xml, const ProductProfile& p, const od::Dictionary& d) {
  auto is_default = [](const std::vector<PdoSpec>& list, std::uint16_t index) {
    return std::any_of(list.begin(), list.end(), [&](const PdoSpec& s) { return s.index == index; });
  };
  for (const PdoSpec& pdo : p.rx_pdos) write_default_pdo(xml, "RxPdo", pdo);
  for (const auto& rule : p.pdo_rules.rx_objects)
    if (!is_default(p.rx_pdos, rule.index)) write_optional_pdo(xml, "RxPdo", rule, d, "RxPDO");
  for (const PdoSpec& pdo : p.tx_pdos) write_default_pdo(xml, "TxPdo", pdo);
  for (const auto& rule : p.pdo_rules.tx_objects)
    if (!is_default(p.tx_pdos, rule.index)) write_optional_pdo(xml, "TxPdo", rule, d, "TxPDO");
}

void write_mailbox(XmlWriter& xml, const ProductProfile& p) {
  const bool coe = (p.mailbox.protocols & ecat::sii::mailbox_protocol::kCoE) != 0;
  const bool foe = p.foe_details != 0;  // what the firmware supports, not the SII protocol word
  if (!coe && !foe) return;
  xml.open("Mailbox");
  xml.attr("DataLinkLayer", "true");
  if (coe) {
    auto flag = [&](int bit) { return (p.coe_details >> bit) & 1 ? "true" : "false"; };
    xml.open("CoE");
    xml.attr("SdoInfo", flag(1));
    xml.attr("PdoAssign", flag(2));
    xml.attr("PdoConfig", flag(3));
    if (p.coe_details & 0x10) xml.attr("PdoUpload", "true");
    if (p.coe_details & 0x20) xml.attr("CompleteAccess", "true");  // only where the product has it
    xml.close();
  }
  if (foe) {
    xml.open("FoE");
    xml.close();
  }
  xml.close();
}

std::string cycle_times_text(const profile::SyncSpec& s) {
  auto us = [](std::uint32_t ns) {
    return ns % 1000000 == 0 ? fmt::format("{} ms", ns / 1000000) : fmt::format("{} us", ns / 1000.0);
  };
  if (!s.cycle_times_ns.empty()) {
    std::string t;
    for (std::uint32_t ns : s.cycle_times_ns) t += (t.empty() ? "" : ", ") + us(ns);
    return t;
  }
  if (s.cycle_step_ns != 0)
    return fmt::format("{} to {} in steps of {}", us(s.cycle_min_ns), us(s.cycle_max_ns), us(s.cycle_step_ns));
  return {};
}

void op_mode(XmlWriter& xml, const char* name, const char* desc, std::uint16_t assign_activate) {
  xml.open("OpMode");
  xml.element("Name", name);
  xml.element("Desc", desc);
  xml.element("AssignActivate", hex(assign_activate, 4));
  if (assign_activate != 0) {
    // SYNC0 cycle = 1 x the master's bus cycle, no extra shift: the master sets both (1C32h/09A0h).
    xml.open("CycleTimeSync0");
    xml.attr("Factor", "1");
    xml.close_with_text("0");
    xml.element("ShiftTimeSync0", "0");
  }
  xml.close();
}

// <Dc>: the product's sync modes. AssignActivate is the 0x0980 word: 0x0000 = DC unit unused
// (free run, SM-synchronous), 0x0300 = cyclic unit + SYNC0, 0x0700 = + SYNC1.
void write_dc(XmlWriter& xml, const ProductProfile& p) {
  const profile::SyncSpec& s = p.sync;
  if (!s.free_run && !s.sm2_event && !s.dc_sync0 && !s.dc_sync1) return;
  xml.open("Dc");
  std::string cycles = cycle_times_text(s);
  for (const auto& limit : s.mode_min_cycle)
    cycles += fmt::format("; mode {} (6060h) needs at least {} us", limit.mode, limit.min_cycle_ns / 1000.0);
  if (!cycles.empty()) xml.comment("Cycle times the drive accepts (1C32h-02h): " + cycles);
  if (s.free_run) op_mode(xml, "FreeRun", "Free Run", 0x0000);
  if (s.sm2_event) op_mode(xml, "SM2", "SM-Synchron", 0x0000);
  if (s.dc_sync0) op_mode(xml, "DC", "DC-Synchron", 0x0300);
  if (s.dc_sync1) op_mode(xml, "DC_SYNC1", "DC-Synchron (SYNC0 and SYNC1)", 0x0700);
  xml.close();
}

// <Eeprom>: the size and the ESC configuration words 0-6 (the configurator adds the CRC of word 7)
// and the bootstrap mailbox (words 0x14-0x17); or the whole SII image as <Data>.
void write_eeprom(XmlWriter& xml, const ProductProfile& p, bool whole_image) {
  const std::vector<std::uint8_t> sii = profile::build_sii_image(p);
  const std::span<const std::uint8_t> bytes(sii);
  xml.open("Eeprom");
  if (whole_image) {
    xml.element("Data", hex_binary(bytes));
  } else {
    xml.element("ByteSize", std::to_string(p.esc.eeprom_bytes));
    xml.element("ConfigData", hex_binary(bytes.first(14)));
    if (p.has_bootstrap && p.mailbox.boot_rx_offset) xml.element("BootStrap", hex_binary(bytes.subspan(0x28, 8)));
  }
  xml.close();
}

// 1C32h/1C33h as a master reads them after power-on: the firmware fills the sync parameters the
// product reports (04h types supported, 05h minimum cycle, 06h calc-and-copy, 09h delay) from its
// sync settings, not from the dictionary's table defaults (firmware/sync/sync_objects.cpp). The ESI
// gives those values, so a configurator and an SDO upload agree.
od::Dictionary reported_values(const ProductProfile& p, const od::Dictionary& d) {
  std::vector<od::ObjectDesc> objects(d.objects().begin(), d.objects().end());
  for (od::ObjectDesc& o : objects) {
    if (o.index != 0x1C32 && o.index != 0x1C33) continue;
    const profile::SyncObjectSpec& s = o.index == 0x1C32 ? p.sync.sm2 : p.sync.sm3;
    const std::uint8_t max = o.max_subindex();
    for (od::EntryDesc& e : o.entries) {
      std::optional<std::uint64_t> v;
      switch (e.subindex) {
        case 0x00: v = max; break;
        case 0x04: v = s.supported_sync_types; break;
        case 0x05: v = s.min_cycle_time_ns; break;
        case 0x06: v = s.calc_and_copy_time_ns; break;
        case 0x09: v = s.delay_time_ns; break;
        default: break;
      }
      if (!v) continue;
      for (std::size_t i = 0; i < e.default_value.size(); ++i)
        e.default_value[i] = static_cast<std::uint8_t>(i < 8 ? *v >> (8 * i) : 0);
    }
  }
  return od::Dictionary::from_objects(std::move(objects), p, /*complete_pdo_objects=*/false);
}

}  // namespace

std::string export_esi(const ProductProfile& p, const od::Dictionary& d, const EsiOptions& options) {
  const profile::Identity& id = p.identity;
  XmlWriter xml;
  xml.comment(fmt::format("{} ({}): generated by `vdrive esi` from profiles/{} ({}); not the vendor's file.",
                          p.title, id.device_name, p.id,
                          options.with_dictionary ? "with object dictionary" : "without object dictionary"));
  xml.open("EtherCATInfo");
  xml.attr("xmlns:xsi", "http://www.w3.org/2001/XMLSchema-instance");
  xml.attr("xsi:noNamespaceSchemaLocation", "EtherCATInfo.xsd");
  xml.attr("Version", "1.6");

  xml.open("Vendor");
  xml.element("Id", hex(id.vendor_id, 8));
  xml.element("Name", id.vendor_name);
  xml.close();

  xml.open("Descriptions");
  xml.open("Groups");
  xml.open("Group");
  xml.element("Type", id.group);
  xml.open("Name");
  xml.attr("LcId", kLcIdEnglish);
  xml.close_with_text(id.group);
  xml.close();
  xml.close();

  xml.open("Devices");
  xml.open("Device");
  xml.attr("Physics", physics(p.esc.port_descriptor));
  xml.open("Type");
  xml.attr("ProductCode", hex(id.product_code, 8));
  xml.attr("RevisionNo", hex(id.revision, 8));
  xml.close_with_text(id.order_code);
  xml.open("Name");
  xml.attr("LcId", kLcIdEnglish);
  xml.close_with_text(id.device_name);
  // Explicit Device ID (SII General flags bit 5): the ESI says so with IdentificationReg134.
  if (p.explicit_device_id) {
    xml.open("Info");
    xml.element("IdentificationReg134", "true");
    xml.close();
  }
  xml.element("GroupType", id.group);

  // 1000h: low word = device profile number (402 for drives), high word = additional information.
  xml.open("Profile");
  xml.element("ProfileNo", std::to_string(id.device_type & 0xFFFF));
  if ((id.device_type >> 16) != 0) xml.element("AddInfo", std::to_string(id.device_type >> 16));
  if (options.with_dictionary && !d.objects().empty()) write_dictionary(xml, reported_values(p, d));
  xml.close();

  // FMMUs in the order the SII FMMU category declares them.
  constexpr const char* kFmmus[] = {"Outputs", "Inputs", "MBoxState"};
  if (!p.fmmu_usage.empty()) {
    for (const std::uint8_t usage : p.fmmu_usage) {
      namespace u = ecat::sii::fmmu_usage;
      xml.element("Fmmu", usage == u::kOutputs ? "Outputs" : usage == u::kInputs ? "Inputs"
                          : usage == u::kMailboxState ? "MBoxState" : "");
    }
  } else {
    for (std::uint8_t i = 0; i < std::min<std::uint8_t>(p.esc.fmmu_count, 3); ++i) xml.element("Fmmu", kFmmus[i]);
  }
  write_sync_managers(xml, p);
  write_pdos(xml, p, d);
  write_mailbox(xml, p);
  write_dc(xml, p);
  write_eeprom(xml, p, options.eeprom_image);
  xml.close();  // Device
  xml.close();  // Devices
  xml.close();  // Descriptions
  xml.close();  // EtherCATInfo
  return xml.str();
}

}  // namespace vdrive::esi
