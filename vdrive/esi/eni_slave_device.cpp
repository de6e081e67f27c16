#include "vdrive/esi/eni_slave_device.hpp"

#include <fmt/core.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "vdrive/esi/esi_error.hpp"
#include "vdrive/esi/esi_import.hpp"

namespace vdrive::esi {
namespace {

using tinyxml2::XMLElement;

std::string who(const EniSlave& s) {
  return fmt::format("slave '{}' (vendor 0x{:08X}, product 0x{:08X}, revision 0x{:08X})", s.name, s.vendor_id,
                     s.product_code, s.revision);
}

[[noreturn]] void refuse(const EniSlave& s, int line, std::string_view element, const std::string& what) {
  throw EsiError(fmt::format("{}:{}: <{}>: {}: {}; it cannot be served from the ENI alone (add its ESI file to an "
                             "--esi-dir)", s.file, line, element, who(s), what));
}

bool outputs(const std::string& type) { return type == "Outputs"; }

std::uint32_t pdo_bits(const EsiPdo& p) {
  std::uint32_t bits = 0;
  for (const EsiPdoEntry& e : p.entries) bits += e.bit_length;
  return bits;
}

class Builder {
public:
  explicit Builder(const EniSlave& s) : s_(s) {}

  EniSlaveDevice build() {
    EsiDevice& d = out_.device;
    d.file = s_.file;
    d.line = s_.line;
    d.vendor_id = s_.vendor_id;
    d.product_code = s_.product_code;
    d.revision = s_.revision;
    d.name = s_.name.empty() ? fmt::format("ENI slave {}", s_.phys_addr.value_or(0)) : s_.name;
    d.physics = s_.physics;
    if (d.physics.empty()) assume("two MII ports (no <Physics>)");
    mailbox();
    process_data();
    synchronisation();
    if (d.sync_managers.empty()) assume("neither a mailbox nor process data (the ENI gives neither): it carries the line");
    d.fmmus = {"Outputs", "Inputs"};
    if (s_.has_mailbox) d.fmmus.emplace_back("MBoxState");
    assume("no behaviour of its own: the process data the master writes and reads is kept as object values");
    objects_for_init_commands();
    return std::move(out_);
  }

private:
  void assume(std::string what) { out_.assumptions.push_back(std::move(what)); }

  void mailbox() {
    EsiDevice& d = out_.device;
    if (!s_.has_mailbox) return;
    auto mailbox_sm = [&](int n, const char* kind, std::uint16_t start, std::uint16_t length, std::uint8_t control) {
      EsiSyncManager m;
      m.kind = kind;
      m.start = start;
      m.default_size = length;
      m.enable = true;
      m.line = s_.mailbox_line;
      const std::optional<EniSmWrite> w = s_.sm_written(n);
      m.control = w ? w->control : control;
      if (!w) assume(fmt::format("SM{} control byte {:02X}h (no init command sets SM{} up)", n, control, n));
      d.sync_managers.push_back(m);
    };
    mailbox_sm(0, "MBoxOut", s_.send_start, s_.send_length, 0x26);
    mailbox_sm(1, "MBoxIn", s_.recv_start, s_.recv_length, 0x22);
    // The Boot-state mailbox, as ESI <Eeprom><BootStrap> gives it (SII words 14h-17h).
    if (s_.boot_mailbox)
      for (const std::uint16_t v : *s_.boot_mailbox) {
        d.boot_strap.push_back(static_cast<std::uint8_t>(v));
        d.boot_strap.push_back(static_cast<std::uint8_t>(v >> 8));
      }
    d.coe = s_.has_protocol("CoE");
    d.foe = s_.has_protocol("FoE");
    d.eoe = s_.has_protocol("EoE");
    d.soe = s_.has_protocol("SoE");
    d.aoe = s_.has_protocol("AoE");
    d.voe = s_.has_protocol("VoE");
    // The CoE services the master's configurator relied on are the ones its commands use.
    for (const EniCoeCommand& c : s_.coe_init_commands) {
      if (c.disabled) continue;
      d.complete_access |= c.complete_access;
      if (c.ccs != 1) continue;
      d.pdo_assign |= c.index == 0x1C12 || c.index == 0x1C13;
      d.pdo_config |= (c.index >= 0x1600 && c.index <= 0x17FF) || (c.index >= 0x1A00 && c.index <= 0x1BFF);
    }
    if (d.coe) assume("CoE without SDO information");
  }

  // The process-data SyncManagers: the ENI's <SmN>, completed from the init commands that set
  // them up; a direction with data but no SyncManager address cannot be served.
  void process_data() {
    EsiDevice& d = out_.device;
    struct Sm {
      int number = 0;
      EsiSyncManager sm;
      std::vector<std::uint16_t> pdos;
    };
    std::vector<Sm> sms;
    for (const EniSmSetting& e : s_.sms) {
      const std::string element = fmt::format("Sm{}", e.number);
      if (s_.has_mailbox && e.number < 2)
        refuse(s_, e.line, element, fmt::format("process data on SM{}, which its <Mailbox> uses", e.number));
      // Without a mailbox the device's SMs count from 0 (below), and its register init commands
      // set up that SM, whatever number the ENI's element has.
      std::optional<EniSmWrite> w = s_.sm_written(e.number);
      if (!w && !s_.has_mailbox) w = s_.sm_written(static_cast<int>(sms.size()));
      Sm x;
      x.number = e.number;
      x.pdos = e.pdos;
      x.sm.kind = e.type;
      x.sm.line = e.line;
      x.sm.enable = e.enable;
      if (e.start) x.sm.start = *e.start;
      else if (w) x.sm.start = w->start;
      else refuse(s_, e.line, element, fmt::format("{} without a <StartAddress>, and no init command sets SM{} up: "
                                                   "the address the device takes its {} at is missing", e.type,
                                                   e.number, outputs(e.type) ? "outputs" : "inputs"));
      const std::uint8_t control = outputs(e.type) ? 0x64 : 0x20;
      x.sm.control = e.control ? *e.control : w ? w->control : control;
      if (!e.control && !w) assume(fmt::format("SM{} control byte {:02X}h (none given)", e.number, control));
      if (e.default_size) x.sm.default_size = *e.default_size;
      else if (w) x.sm.default_size = w->length;
      sms.push_back(std::move(x));
    }
    // A direction with data and no <SmN>: an init command that sets a buffered SM of that direction up.
    for (const bool out : {true, false}) {
      const std::uint32_t bits = out ? s_.output_bits : s_.input_bits;
      const std::vector<EsiPdo>& pdos = out ? s_.rx_pdos : s_.tx_pdos;
      const bool has_data = bits > 0 || std::any_of(pdos.begin(), pdos.end(), [](const EsiPdo& p) { return pdo_bits(p) > 0; });
      const char* type = out ? "Outputs" : "Inputs";
      if (!has_data || std::any_of(sms.begin(), sms.end(), [&](const Sm& x) { return x.sm.kind == type; })) continue;
      bool found = false;
      for (int n = s_.has_mailbox ? 2 : 0; n < 16 && !found; ++n) {
        const std::optional<EniSmWrite> w = s_.sm_written(n);
        if (!w || (w->control & 0x03) != 0 || ((w->control & 0x0C) == 0x04) != out) continue;
        if (std::any_of(sms.begin(), sms.end(), [&](const Sm& x) { return x.number == n; })) continue;
        sms.push_back(Sm{n, EsiSyncManager{type, w->start, w->length, 0, 0, w->control, w->enable, s_.process_data_line}, {}});
        found = true;
      }
      if (!found)
        refuse(s_, s_.process_data_line, "ProcessData",
               fmt::format("{} bits of {} but no <SmN> of Type {} with a <StartAddress> and no init command that "
                           "sets such a SyncManager up: the address the device takes them at is missing",
                           bits > 0 ? bits : 0, out ? "outputs" : "inputs", type));
    }
    std::sort(sms.begin(), sms.end(), [](const Sm& a, const Sm& b) { return a.number < b.number; });
    // SyncManager numbers: with a mailbox as the ENI gives them (a gap gets a disabled SM of no
    // size); without one from 0 up, as simple I/O has them.
    std::map<int, int> number;  // ENI SM number -> the device's
    for (const Sm& x : sms) {
      int n = static_cast<int>(d.sync_managers.size());
      if (s_.has_mailbox) {
        while (n < x.number) {
          EsiSyncManager gap = x.sm;
          gap.kind = n % 2 == 0 ? "Outputs" : "Inputs";
          gap.default_size = 0;
          gap.enable = false;
          d.sync_managers.push_back(gap);
          n = static_cast<int>(d.sync_managers.size());
        }
      } else if (n != x.number) {
        assume(fmt::format("SM{} of the ENI is the device's SM{} (no mailbox: process data from SM0 up)", x.number, n));
      }
      number[x.number] = n;
      d.sync_managers.push_back(x.sm);
    }
    // PDOs: assigned to the SM their Sm attribute or an <SmN><Pdo> names.
    auto assign = [&](std::vector<EsiPdo> pdos, const char* type, const char* element) {
      for (EsiPdo& p : pdos) {
        if (!p.sm)
          for (const Sm& x : sms)
            if (std::find(x.pdos.begin(), x.pdos.end(), p.index) != x.pdos.end()) p.sm = static_cast<std::uint8_t>(x.number);
        if (!p.sm) continue;
        const auto it = number.find(*p.sm);
        if (it == number.end())
          refuse(s_, p.line, element, fmt::format("PDO {:04X}h is assigned to SM{}, which the ENI does not set up for "
                                                  "process data", p.index, *p.sm));
        if (d.sync_managers[static_cast<std::size_t>(it->second)].kind != type)
          refuse(s_, p.line, element, fmt::format("PDO {:04X}h is assigned to SM{}, an SM of the other direction",
                                                  p.index, *p.sm));
        p.sm = static_cast<std::uint8_t>(it->second);
      }
      // None assigned and one SM of the direction: the ENI lists the PDOs the master maps.
      const bool none = std::none_of(pdos.begin(), pdos.end(), [](const EsiPdo& p) { return p.sm.has_value(); });
      const auto count = std::count_if(d.sync_managers.begin(), d.sync_managers.end(),
                                       [&](const EsiSyncManager& m) { return m.kind == type && m.enable; });
      if (none && !pdos.empty() && count == 1) {
        for (std::size_t i = 0; i < d.sync_managers.size(); ++i)
          if (d.sync_managers[i].kind == type && d.sync_managers[i].enable)
            for (EsiPdo& p : pdos) p.sm = static_cast<std::uint8_t>(i);
        assume(fmt::format("its {} PDOs assigned to the one {} SyncManager (no Sm attribute, no <Pdo>)", element, type));
      }
      return pdos;
    };
    d.rx_pdos = assign(s_.rx_pdos, "Outputs", "RxPdo");
    d.tx_pdos = assign(s_.tx_pdos, "Inputs", "TxPdo");
    // A size not given: what its PDOs map, else what <Send>/<Recv> says.
    for (std::size_t i = 0; i < d.sync_managers.size(); ++i) {
      EsiSyncManager& m = d.sync_managers[i];
      if (m.default_size != 0 || !m.enable || m.kind.rfind("MBox", 0) == 0) continue;
      std::uint32_t bits = 0;
      for (const EsiPdo& p : m.kind == "Outputs" ? d.rx_pdos : d.tx_pdos)
        if (p.sm == i) bits += pdo_bits(p);
      if (bits == 0) bits = m.kind == "Outputs" ? s_.output_bits : s_.input_bits;
      m.default_size = static_cast<std::uint16_t>(std::min<std::uint32_t>((bits + 7) / 8, 0xFFFF));
    }
  }

  void synchronisation() {
    EsiDevice& d = out_.device;
    if (const std::optional<std::uint16_t> a = s_.dc_activation()) {
      d.has_dc = true;
      d.op_modes.push_back(EsiOpMode{"DC", "from the ENI's init commands", *a, 1, 0, 0, 0});
    } else if (s_.has_dc && s_.cycle_time0 != 0) {
      d.has_dc = true;
      d.op_modes.push_back(EsiOpMode{"DC", "assumed", 0x0300, 1, 0, 0, 0});
      assume("DC with SYNC0 (AssignActivate 0300h: <DC> gives a cycle time, no init command writes 0981h)");
    }
  }

  // Objects the CoE init commands download that the device would not have: created, so the
  // master's start-up succeeds. The dictionary it would have is the import of what is known so far.
  void objects_for_init_commands() {
    EsiDevice& d = out_.device;
    const std::vector<EniCoeCommand>& cmds = s_.coe_init_commands;
    if (!d.coe || std::none_of(cmds.begin(), cmds.end(), [](const EniCoeCommand& c) { return c.ccs == 1 && !c.disabled; }))
      return;
    const ImportedDevice known = import_device(d);
    std::map<std::uint16_t, od::ObjectDesc> made;
    for (const EniCoeCommand& c : cmds) {
      if (c.ccs != 1 || c.disabled || c.data.empty() || known.dictionary->find(c.index) != nullptr) continue;
      if (c.complete_access) {
        out_.created.push_back(fmt::format("{:04X}h not created: its init command (line {}) writes it with complete "
                                           "access, and the ENI does not give its entries", c.index, c.line));
        continue;
      }
      std::uint16_t write = 0;
      for (const std::string& t : c.transitions)
        write |= (t == "SO" || t == "OS") ? od::access::kWriteSafeOp : od::access::kWritePreOp;
      if (write == 0) write = od::access::kWritePreOp;
      od::ObjectDesc& o = made[c.index];
      o.index = c.index;
      if (o.name.empty()) o.name = c.comment.empty() ? fmt::format("ENI init command object {:04X}h", c.index) : c.comment;
      if (const auto e = std::find_if(o.entries.begin(), o.entries.end(), [&](const od::EntryDesc& x) { return x.subindex == c.subindex; });
          e != o.entries.end()) {
        e->access |= write;
        continue;
      }
      od::EntryDesc e;
      e.index = c.index;
      e.subindex = c.subindex;
      e.name = c.comment.empty() ? fmt::format("SubIndex {:03}", c.subindex) : c.comment;
      const std::size_t n = c.data.size();
      e.type = n == 1 ? od::DataType::Unsigned8 : n == 2 ? od::DataType::Unsigned16 : n == 4 ? od::DataType::Unsigned32
             : n == 8 ? od::DataType::Unsigned64 : od::DataType::OctetString;
      e.bit_length = static_cast<std::uint16_t>(std::min<std::size_t>(8 * n, 0xFFF8));
      e.access = static_cast<std::uint16_t>(od::access::kReadAll | write);
      e.value_bytes = static_cast<std::uint32_t>(std::max<std::size_t>(1, e.bit_length / 8));
      e.default_value.assign(e.value_bytes, 0);
      o.entries.push_back(std::move(e));
      out_.created.push_back(fmt::format("{:04X}h:{:02X}h created for its CoE init command (line {}): {}, readable, "
                                         "writable in {}", c.index, c.subindex, c.line, od::short_name(o.entries.back().type),
                                         (write & od::access::kWriteSafeOp) ? "Safe-Op" : "Pre-Op"));
    }
    for (auto& [index, o] : made) {
      std::sort(o.entries.begin(), o.entries.end(), [](const od::EntryDesc& a, const od::EntryDesc& b) { return a.subindex < b.subindex; });
      // A record: subindex 0 gives the highest subindex (the master may write it as well).
      if (o.entries.back().subindex != 0) {
        o.code = od::ObjectCode::Record;
        if (o.entries.front().subindex != 0) {
          od::EntryDesc sub0;
          sub0.index = index;
          sub0.name = "SubIndex 000";
          sub0.access = od::access::kReadAll;
          sub0.synthesized = true;
          sub0.default_value = {o.entries.back().subindex};
          o.entries.insert(o.entries.begin(), std::move(sub0));
        }
      }
      d.objects.push_back(std::move(o));
    }
    std::sort(d.objects.begin(), d.objects.end(), [](const od::ObjectDesc& a, const od::ObjectDesc& b) { return a.index < b.index; });
  }

  const EniSlave& s_;
  EniSlaveDevice out_;
};

}  // namespace

EniSlaveDevice eni_slave_device(const EniSlave& slave) { return Builder(slave).build(); }

bool is_eni_slave_reference(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower.find(".xml#") != std::string::npos;
}

std::string eni_slave_reference(const std::string& eni_path, std::uint16_t phys_addr) {
  return fmt::format("{}#{}", eni_path, phys_addr);
}

EniSlaveDevice load_eni_slave_device(std::string_view reference) {
  const std::size_t hash = reference.rfind('#');
  const std::string path(reference.substr(0, hash));
  const std::string_view number = reference.substr(hash + 1);
  unsigned phys = 0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), phys);
  if (number.empty() || ec != std::errc() || end != number.data() + number.size() || phys > 0xFFFF)
    throw EsiError(fmt::format("'{}': after '#' the slave's <PhysAddr> (decimal), e.g. machine.xml#1003", reference));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw EsiError(fmt::format("{}: cannot read the ENI file", path));
  std::ostringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  tinyxml2::XMLDocument doc;
  if (doc.Parse(s.data(), s.size()) != tinyxml2::XML_SUCCESS)
    throw EsiError(fmt::format("{}:{}: not well-formed XML: {}", path, doc.ErrorLineNum(),
                               doc.ErrorStr() != nullptr ? doc.ErrorStr() : "parse error"));
  const XmlReading xml(path);
  const XMLElement* root = doc.RootElement();
  if (root == nullptr || std::string_view(root->Name()) != "EtherCATConfig")
    xml.fail(root, "not an ENI file: the root element is not <EtherCATConfig>");
  const XMLElement* config = xml.required(root, "Config");
  for (const XMLElement* sl = config->FirstChildElement("Slave"); sl; sl = sl->NextSiblingElement("Slave"))
    if (xml.optional_number(XmlReading::child(sl, "Info"), "PhysAddr", 0, 0xFFFF) == static_cast<std::int64_t>(phys))
      return eni_slave_device(read_eni_slave(xml, sl));
  throw EsiError(fmt::format("{}: no <Slave> with <PhysAddr> {}", path, phys));
}

}  // namespace vdrive::esi
