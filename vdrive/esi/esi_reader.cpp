#include "vdrive/esi/esi_reader.hpp"

#include <fmt/core.h>
#include <tinyxml2.h>

#include <fstream>
#include <limits>
#include <sstream>

#include "vdrive/esi/esi_dictionary_reader.hpp"
#include "vdrive/esi/xml_reading.hpp"

namespace vdrive::esi {
namespace {

using tinyxml2::XMLElement;
constexpr std::int64_t kU8 = 0xFF, kU16 = 0xFFFF, kU32 = 0xFFFFFFFF;

class DeviceReader {
public:
  explicit DeviceReader(const XmlReading& xml) : xml_(xml) {}

  EsiDevice read(const XMLElement* d, const XMLElement* vendor, const XMLElement* groups) {
    EsiDevice dev;
    dev.file = xml_.file();
    dev.line = d->GetLineNum();
    dev.vendor_id = static_cast<std::uint32_t>(xml_.number(xml_.required(vendor, "Id"), 0, kU32));
    dev.vendor_name = XmlReading::english(vendor, "Name");
    const XMLElement* type = xml_.required(d, "Type");
    dev.product_code = static_cast<std::uint32_t>(xml_.optional_attribute(type, "ProductCode", 0, kU32).value_or(0));
    dev.revision = static_cast<std::uint32_t>(xml_.optional_attribute(type, "RevisionNo", 0, kU32).value_or(0));
    dev.type_text = XmlReading::text(type);
    dev.name = XmlReading::english(d, "Name");
    if (dev.name.empty()) dev.name = dev.type_text;
    dev.group_type = XmlReading::text(XmlReading::child(d, "GroupType"));
    dev.group_name = group_name(groups, dev.group_type);
    if (const char* physics = d->Attribute("Physics")) dev.physics = physics;

    if (const XMLElement* profile = XmlReading::child(d, "Profile")) {
      dev.profile_no = static_cast<std::uint32_t>(xml_.optional_number(profile, "ProfileNo", 0, kU16).value_or(0));
      dev.add_info = static_cast<std::uint32_t>(xml_.optional_number(profile, "AddInfo", 0, kU16).value_or(0));
      if (const XMLElement* dictionary = XmlReading::child(profile, "Dictionary")) {
        dev.has_dictionary = true;
        dev.objects = read_dictionary(xml_, dictionary);
      } else if (XmlReading::child(profile, "DictionaryFile") != nullptr) {
        xml_.fail(XmlReading::child(profile, "DictionaryFile"),
                  "a dictionary in a file of its own is not read; put the <Dictionary> into the device");
      }
    }
    for (const XMLElement* f = d->FirstChildElement("Fmmu"); f; f = f->NextSiblingElement("Fmmu"))
      dev.fmmus.push_back(XmlReading::text(f));
    for (const XMLElement* s = d->FirstChildElement("Sm"); s; s = s->NextSiblingElement("Sm"))
      dev.sync_managers.push_back(read_sm(s));
    for (const XMLElement* p = d->FirstChildElement("RxPdo"); p; p = p->NextSiblingElement("RxPdo"))
      dev.rx_pdos.push_back(read_pdo(xml_, p));
    for (const XMLElement* p = d->FirstChildElement("TxPdo"); p; p = p->NextSiblingElement("TxPdo"))
      dev.tx_pdos.push_back(read_pdo(xml_, p));
    read_mailbox(XmlReading::child(d, "Mailbox"), dev);
    if (const XMLElement* dc = XmlReading::child(d, "Dc")) {
      dev.has_dc = true;
      for (const XMLElement* m = dc->FirstChildElement("OpMode"); m; m = m->NextSiblingElement("OpMode"))
        dev.op_modes.push_back(read_op_mode(m));
    }
    read_eeprom(XmlReading::child(d, "Eeprom"), dev);
    if (const XMLElement* info = XmlReading::child(d, "Info")) {
      const auto ado = xml_.optional_number(info, "IdentificationAdo", 0, kU16);
      const XMLElement* reg134 = XmlReading::child(info, "IdentificationReg134");
      dev.explicit_device_id = ado == 0x0134 || (reg134 != nullptr && (XmlReading::text(reg134) == "true" ||
                                                                         XmlReading::text(reg134) == "1"));
    }
    return dev;
  }

private:
  static std::string group_name(const XMLElement* groups, const std::string& type) {
    for (const XMLElement* g = XmlReading::child(groups, "Group"); g; g = g->NextSiblingElement("Group"))
      if (XmlReading::text(XmlReading::child(g, "Type")) == type) return XmlReading::english(g, "Name");
    return type;
  }

  EsiSyncManager read_sm(const XMLElement* s) const {
    EsiSyncManager sm;
    sm.line = s->GetLineNum();
    sm.kind = XmlReading::text(s);
    sm.start = static_cast<std::uint16_t>(xml_.optional_attribute(s, "StartAddress", 0, kU16).value_or(0));
    sm.default_size = static_cast<std::uint16_t>(xml_.optional_attribute(s, "DefaultSize", 0, kU16).value_or(0));
    sm.min_size = static_cast<std::uint16_t>(xml_.optional_attribute(s, "MinSize", 0, kU16).value_or(0));
    sm.max_size = static_cast<std::uint16_t>(xml_.optional_attribute(s, "MaxSize", 0, kU16).value_or(0));
    sm.control = static_cast<std::uint8_t>(xml_.optional_attribute(s, "ControlByte", 0, kU8).value_or(0));
    // No text (as IgH's `ethercat xml` writes them): the kind follows from the control byte's mode
    // (bits 1-0: 10b mailbox, 00b buffered) and direction (bits 3-2: 01b written by the master).
    if (sm.kind.empty() && s->Attribute("ControlByte") != nullptr) {
      const bool mailbox = (sm.control & 0x03) == 0x02, written = (sm.control & 0x0C) == 0x04;
      sm.kind = mailbox ? (written ? "MBoxOut" : "MBoxIn") : (written ? "Outputs" : "Inputs");
    }
    if (sm.kind != "MBoxOut" && sm.kind != "MBoxIn" && sm.kind != "Outputs" && sm.kind != "Inputs")
      xml_.fail(s, fmt::format("'{}': expected MBoxOut, MBoxIn, Outputs or Inputs", sm.kind));
    sm.enable = xml_.optional_attribute(s, "Enable", 0, kU8).value_or(0) != 0;
    return sm;
  }

  void read_mailbox(const XMLElement* m, EsiDevice& dev) const {
    if (m == nullptr) return;
    const XMLElement* coe = XmlReading::child(m, "CoE");
    dev.coe = coe != nullptr;
    dev.foe = XmlReading::child(m, "FoE") != nullptr;
    dev.eoe = XmlReading::child(m, "EoE") != nullptr;
    dev.soe = XmlReading::child(m, "SoE") != nullptr;
    dev.aoe = XmlReading::child(m, "AoE") != nullptr;
    dev.voe = XmlReading::child(m, "VoE") != nullptr;
    if (coe == nullptr) return;
    dev.sdo_info = xml_.flag(coe, "SdoInfo", false);
    dev.pdo_assign = xml_.flag(coe, "PdoAssign", false);
    dev.pdo_config = xml_.flag(coe, "PdoConfig", false);
    dev.pdo_upload = xml_.flag(coe, "PdoUpload", false);
    dev.complete_access = xml_.flag(coe, "CompleteAccess", false);
  }

  EsiOpMode read_op_mode(const XMLElement* m) const {
    constexpr std::int64_t kI32Lo = std::numeric_limits<std::int32_t>::min(), kI32Hi = std::numeric_limits<std::int32_t>::max();
    EsiOpMode mode;
    mode.name = XmlReading::text(XmlReading::child(m, "Name"));
    mode.description = XmlReading::english(m, "Desc");
    mode.assign_activate = static_cast<std::uint16_t>(xml_.number(xml_.required(m, "AssignActivate"), 0, kU16));
    if (const XMLElement* c = XmlReading::child(m, "CycleTimeSync0"))
      mode.cycle_time_sync0_factor = static_cast<std::int32_t>(xml_.optional_attribute(c, "Factor", kI32Lo, kI32Hi).value_or(1));
    mode.shift_time_sync0 = static_cast<std::int32_t>(xml_.optional_number(m, "ShiftTimeSync0", kI32Lo, kI32Hi).value_or(0));
    if (const XMLElement* c = XmlReading::child(m, "CycleTimeSync1"))
      mode.cycle_time_sync1_factor = static_cast<std::int32_t>(xml_.optional_attribute(c, "Factor", kI32Lo, kI32Hi).value_or(0));
    mode.shift_time_sync1 = static_cast<std::int32_t>(xml_.optional_number(m, "ShiftTimeSync1", kI32Lo, kI32Hi).value_or(0));
    return mode;
  }

  void read_eeprom(const XMLElement* e, EsiDevice& dev) const {
    if (e == nullptr) return;
    if (const auto size = xml_.optional_number(e, "ByteSize", 128, 0x10000)) dev.eeprom_bytes = static_cast<std::uint32_t>(*size);
    if (const XMLElement* c = XmlReading::child(e, "ConfigData")) dev.config_data = xml_.hex_binary(c);
    if (const XMLElement* b = XmlReading::child(e, "BootStrap")) {
      dev.boot_strap = xml_.hex_binary(b);
      if (dev.boot_strap.size() != 8) xml_.fail(b, fmt::format("{} bytes; the bootstrap mailbox is 8 (SII words 14h-17h)",
                                                                 dev.boot_strap.size()));
    }
    if (const XMLElement* d = XmlReading::child(e, "Data")) {
      dev.eeprom_data = xml_.hex_binary(d);
      if (dev.eeprom_data.size() < 128) xml_.fail(d, fmt::format("{} bytes; an SII image has at least 128 (64 words)",
                                                                   dev.eeprom_data.size()));
      if (dev.eeprom_data.size() > 0x10000) xml_.fail(d, "more than 64 KiB");
    }
  }

  const XmlReading& xml_;
};

}  // namespace

EsiPdo read_pdo(const XmlReading& xml, const XMLElement* p) {
  EsiPdo pdo;
  pdo.line = p->GetLineNum();
  pdo.index = static_cast<std::uint16_t>(xml.number(xml.required(p, "Index"), 0, kU16));
  pdo.name = XmlReading::english(p, "Name");
  pdo.fixed = xml.flag(p, "Fixed", false);
  pdo.mandatory = xml.flag(p, "Mandatory", false);
  if (const auto sm = xml.optional_attribute(p, "Sm", 0, 15)) pdo.sm = static_cast<std::uint8_t>(*sm);
  for (const XMLElement* x = p->FirstChildElement("Exclude"); x; x = x->NextSiblingElement("Exclude"))
    pdo.exclude.push_back(static_cast<std::uint16_t>(xml.number(x, 0, kU16)));
  for (const XMLElement* e = p->FirstChildElement("Entry"); e; e = e->NextSiblingElement("Entry")) {
    EsiPdoEntry entry;
    entry.line = e->GetLineNum();
    entry.index = static_cast<std::uint16_t>(xml.number(xml.required(e, "Index"), 0, kU16));
    entry.subindex = static_cast<std::uint8_t>(xml.optional_number(e, "SubIndex", 0, kU8).value_or(0));
    entry.bit_length = static_cast<std::uint16_t>(xml.number(xml.required(e, "BitLen"), 1, kU8));
    entry.name = XmlReading::english(e, "Name");
    entry.data_type = XmlReading::text(XmlReading::child(e, "DataType"));
    pdo.entries.push_back(std::move(entry));
  }
  return pdo;
}

std::vector<EsiDevice> parse_esi(std::string_view text, const std::string& file) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
    throw EsiError(fmt::format("{}:{}: not well-formed XML: {}", file, doc.ErrorLineNum(),
                               doc.ErrorStr() != nullptr ? doc.ErrorStr() : "parse error"));
  const XmlReading xml(file);
  const XMLElement* root = doc.RootElement();
  if (root == nullptr || std::string_view(root->Name()) != "EtherCATInfo")
    xml.fail(root, "not an ESI file: the root element is not <EtherCATInfo>");
  const XMLElement* vendor = xml.required(root, "Vendor");
  const XMLElement* descriptions = xml.required(root, "Descriptions");
  const XMLElement* groups = XmlReading::child(descriptions, "Groups");
  const XMLElement* devices = xml.required(descriptions, "Devices");
  std::vector<EsiDevice> out;
  DeviceReader reader(xml);
  for (const XMLElement* d = devices->FirstChildElement("Device"); d; d = d->NextSiblingElement("Device"))
    out.push_back(reader.read(d, vendor, groups));
  if (out.empty()) xml.fail(devices, "no <Device>");
  return out;
}

std::vector<EsiDevice> read_esi_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw EsiError(fmt::format("{}: cannot read the ESI file", path));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_esi(text.str(), path);
}

}  // namespace vdrive::esi
