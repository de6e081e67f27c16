#include "vdrive/esi/eni_slave.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>

#include "ethercat/little_endian.hpp"
#include "vdrive/esi/esi_reader.hpp"

namespace vdrive::esi {
namespace {

using tinyxml2::XMLElement;
constexpr std::int64_t kU8 = 0xFF, kU16 = 0xFFFF, kU32 = 0xFFFFFFFF;
// ETG.2100 writes identities as xs:int: a product code with the top bit set may come negative.
constexpr std::int64_t kI32Lo = -2147483648LL;

std::uint32_t u32(const XmlReading& xml, const XMLElement* e) {
  return static_cast<std::uint32_t>(xml.number(e, kI32Lo, kU32));
}

// An element's xs:boolean text.
bool boolean(const XmlReading& xml, const XMLElement* e, bool otherwise) {
  if (e == nullptr) return otherwise;
  const std::string t = XmlReading::text(e);
  if (t == "true" || t == "1") return true;
  if (t == "false" || t == "0") return false;
  xml.fail(e, fmt::format("'{}' is not a boolean (true, false, 1 or 0)", t));
}

std::vector<std::string> transitions(const XMLElement* cmd) {
  std::vector<std::string> out;
  for (const XMLElement* t = cmd->FirstChildElement("Transition"); t; t = t->NextSiblingElement("Transition"))
    out.push_back(XmlReading::text(t));
  return out;
}

std::vector<std::uint8_t> data_of(const XmlReading& xml, const XMLElement* cmd) {
  if (const XMLElement* d = XmlReading::child(cmd, "Data")) return xml.hex_binary(d);
  if (const auto n = xml.optional_number(cmd, "DataLength", 0, kU16)) return std::vector<std::uint8_t>(static_cast<std::size_t>(*n), 0);
  return {};
}

EniRegisterCommand register_command(const XmlReading& xml, const XMLElement* c) {
  EniRegisterCommand r;
  r.line = c->GetLineNum();
  r.transitions = transitions(c);
  r.comment = XmlReading::text(XmlReading::child(c, "Comment"));
  r.cmd = static_cast<std::uint8_t>(xml.number(xml.required(c, "Cmd"), 0, 14));
  // Logical commands (<Addr>) address no register of this slave.
  if (const XMLElement* ado = XmlReading::child(c, "Ado")) r.ado = static_cast<std::uint16_t>(xml.number(ado, 0, kU16));
  r.data = data_of(xml, c);
  return r;
}

EniCoeCommand coe_command(const XmlReading& xml, const XMLElement* c) {
  EniCoeCommand r;
  r.line = c->GetLineNum();
  r.transitions = transitions(c);
  r.comment = XmlReading::text(XmlReading::child(c, "Comment"));
  r.ccs = static_cast<std::uint8_t>(xml.optional_number(c, "Ccs", 0, 7).value_or(1));
  r.index = static_cast<std::uint16_t>(xml.number(xml.required(c, "Index"), 0, kU16));
  r.subindex = static_cast<std::uint8_t>(xml.optional_number(c, "SubIndex", 0, kU8).value_or(0));
  r.data = data_of(xml, c);
  r.complete_access = xml.flag(c, "CompleteAccess", false);
  r.disabled = boolean(xml, XmlReading::child(c, "Disabled"), false);
  return r;
}

void read_mailbox(const XmlReading& xml, const XMLElement* m, EniSlave& s) {
  s.has_mailbox = true;
  s.mailbox_line = m->GetLineNum();
  const XMLElement* send = xml.required(m, "Send");
  const XMLElement* recv = xml.required(m, "Recv");
  s.send_start = static_cast<std::uint16_t>(xml.number(xml.required(send, "Start"), 0, kU16));
  s.send_length = static_cast<std::uint16_t>(xml.number(xml.required(send, "Length"), 0, kU16));
  s.recv_start = static_cast<std::uint16_t>(xml.number(xml.required(recv, "Start"), 0, kU16));
  s.recv_length = static_cast<std::uint16_t>(xml.number(xml.required(recv, "Length"), 0, kU16));
  if (const XMLElement* boot = XmlReading::child(m, "BootStrap")) {
    const XMLElement* bs = xml.required(boot, "Send");
    const XMLElement* br = xml.required(boot, "Recv");
    s.boot_mailbox = std::array<std::uint16_t, 4>{
        static_cast<std::uint16_t>(xml.number(xml.required(bs, "Start"), 0, kU16)),
        static_cast<std::uint16_t>(xml.number(xml.required(bs, "Length"), 0, kU16)),
        static_cast<std::uint16_t>(xml.number(xml.required(br, "Start"), 0, kU16)),
        static_cast<std::uint16_t>(xml.number(xml.required(br, "Length"), 0, kU16))};
  }
  for (const XMLElement* p = m->FirstChildElement("Protocol"); p; p = p->NextSiblingElement("Protocol"))
    s.protocols.push_back(XmlReading::text(p));
  // A protocol with init commands of its own (<CoE>, <SoE>, ...) is one the device speaks.
  for (const char* p : {"AoE", "EoE", "CoE", "FoE", "SoE", "VoE"})
    if (XmlReading::child(m, p) != nullptr && !s.has_protocol(p)) s.protocols.emplace_back(p);
  if (const XMLElement* cmds = XmlReading::child(XmlReading::child(m, "CoE"), "InitCmds"))
    for (const XMLElement* c = cmds->FirstChildElement("InitCmd"); c; c = c->NextSiblingElement("InitCmd"))
      s.coe_init_commands.push_back(coe_command(xml, c));
}

void read_process_data(const XmlReading& xml, const XMLElement* pd, EniSlave& s) {
  s.process_data_line = pd->GetLineNum();
  for (const XMLElement* e = pd->FirstChildElement("Send"); e; e = e->NextSiblingElement("Send"))
    s.output_bits += static_cast<std::uint32_t>(xml.optional_number(e, "BitLength", 0, kU32).value_or(0));
  for (const XMLElement* e = pd->FirstChildElement("Recv"); e; e = e->NextSiblingElement("Recv"))
    s.input_bits += static_cast<std::uint32_t>(xml.optional_number(e, "BitLength", 0, kU32).value_or(0));
  for (const XMLElement* e = pd->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string_view name = e->Name();
    if (name == "RxPdo") s.rx_pdos.push_back(read_pdo(xml, e));
    if (name == "TxPdo") s.tx_pdos.push_back(read_pdo(xml, e));
    // <Sm0> .. <Sm15>
    if (name.size() < 3 || name.size() > 4 || name.substr(0, 2) != "Sm" ||
        !std::all_of(name.begin() + 2, name.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      continue;
    EniSmSetting sm;
    sm.line = e->GetLineNum();
    sm.number = std::stoi(std::string(name.substr(2)));
    if (sm.number > 15) xml.fail(e, "an ESC has SyncManagers 0 to 15");
    if (std::any_of(s.sms.begin(), s.sms.end(), [&](const EniSmSetting& x) { return x.number == sm.number; }))
      xml.fail(e, fmt::format("SM{} is given twice", sm.number));
    sm.type = XmlReading::text(XmlReading::child(e, "Type"));
    if (sm.type != "Outputs" && sm.type != "Inputs")
      xml.fail(e, fmt::format("<Type> '{}': expected Outputs or Inputs", sm.type));
    if (const auto v = xml.optional_number(e, "StartAddress", 0, kU16)) sm.start = static_cast<std::uint16_t>(*v);
    if (const auto v = xml.optional_number(e, "DefaultSize", 0, kU16)) sm.default_size = static_cast<std::uint16_t>(*v);
    if (const auto v = xml.optional_number(e, "ControlByte", 0, kU8)) sm.control = static_cast<std::uint8_t>(*v);
    sm.enable = boolean(xml, XmlReading::child(e, "Enable"), true);
    for (const XMLElement* p = e->FirstChildElement("Pdo"); p; p = p->NextSiblingElement("Pdo"))
      sm.pdos.push_back(static_cast<std::uint16_t>(xml.number(p, 0, kU16)));
    s.sms.push_back(std::move(sm));
  }
}

}  // namespace

bool EniRegisterCommand::is_write() const {
  // ETG.1000.4: APWR 2, APRW 3, FPWR 5, FPRW 6, BWR 8, BRW 9, ARMW 13, FRMW 14.
  return cmd == 2 || cmd == 3 || cmd == 5 || cmd == 6 || cmd == 8 || cmd == 9 || cmd == 13 || cmd == 14;
}

bool EniRegisterCommand::runs_at(std::string_view transition) const {
  return std::find(transitions.begin(), transitions.end(), transition) != transitions.end();
}

bool EniSlave::has_protocol(std::string_view p) const {
  return std::find(protocols.begin(), protocols.end(), p) != protocols.end();
}

std::optional<EniSmWrite> EniSlave::sm_written(int n) const {
  const std::size_t base = 0x0800 + 8 * static_cast<std::size_t>(n);
  for (const EniRegisterCommand& c : init_commands) {
    if (!c.is_write() || c.ado > base || c.ado + c.data.size() < base + 5) continue;
    const std::size_t at = base - c.ado;
    EniSmWrite w;
    w.start = ecat::get_le16(c.data, at);
    w.length = ecat::get_le16(c.data, at + 2);
    w.control = c.data[at + 4];
    if (c.data.size() > at + 6) w.enable = (c.data[at + 6] & 0x01) != 0;
    w.line = c.line;
    if (w.length != 0) return w;
  }
  return std::nullopt;
}

std::optional<std::uint16_t> EniSlave::dc_activation() const {
  for (const EniRegisterCommand& c : init_commands) {
    if (!c.is_write() || c.ado > 0x0981 || c.ado + c.data.size() <= 0x0981) continue;
    const std::uint8_t activation = c.data[0x0981 - c.ado];
    const std::uint8_t cyclic = c.ado <= 0x0980 ? c.data[0x0980 - c.ado] : 0;
    if (activation != 0) return static_cast<std::uint16_t>(activation << 8 | cyclic);
  }
  return std::nullopt;
}

EniSlave read_eni_slave(const XmlReading& xml, const XMLElement* sl) {
  EniSlave s;
  s.file = xml.file();
  s.line = sl->GetLineNum();
  const XMLElement* info = xml.required(sl, "Info");
  s.name = XmlReading::text(XmlReading::child(info, "Name"));
  if (const auto v = xml.optional_number(info, "PhysAddr", 0, kU16)) s.phys_addr = static_cast<std::uint16_t>(*v);
  s.vendor_id = u32(xml, xml.required(info, "VendorId"));
  s.product_code = u32(xml, xml.required(info, "ProductCode"));
  if (const XMLElement* r = XmlReading::child(info, "RevisionNo")) s.revision = u32(xml, r);
  s.physics = XmlReading::text(XmlReading::child(info, "Physics"));
  if (const XMLElement* pd = XmlReading::child(sl, "ProcessData")) read_process_data(xml, pd, s);
  if (const XMLElement* m = XmlReading::child(sl, "Mailbox")) read_mailbox(xml, m, s);
  if (const XMLElement* cmds = XmlReading::child(sl, "InitCmds"))
    for (const XMLElement* c = cmds->FirstChildElement("InitCmd"); c; c = c->NextSiblingElement("InitCmd"))
      s.init_commands.push_back(register_command(xml, c));
  if (const XMLElement* dc = XmlReading::child(sl, "DC")) {
    s.has_dc = true;
    s.dc_line = dc->GetLineNum();
    s.reference_clock = boolean(xml, XmlReading::child(dc, "ReferenceClock"), false);
    s.cycle_time0 = static_cast<std::uint32_t>(xml.optional_number(dc, "CycleTime0", 0, kU32).value_or(0));
  }
  return s;
}

}  // namespace vdrive::esi
