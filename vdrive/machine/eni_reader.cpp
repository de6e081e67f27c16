#include "vdrive/machine/eni_reader.hpp"

#include <fmt/core.h>
#include <tinyxml2.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "vdrive/esi/eni_slave.hpp"
#include "vdrive/esi/eni_slave_device.hpp"
#include "vdrive/esi/esi_error.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/esi/esi_reader.hpp"
#include "vdrive/esi/xml_reading.hpp"
#include "vdrive/machine/eni_init_commands.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::machine {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

struct Identity {
  std::uint32_t vendor = 0, product = 0, revision = 0;
};

struct Candidate {
  std::string reference;  // FILE.xml:0xPRODUCT:0xREVISION
  Identity id;
  std::uint32_t mask = 0xFFFFFFFF;  // product codes it covers (built-in products)
};

// Every device of every ESI file under `dirs`; unreadable files are skipped with a note.
std::vector<Candidate> esi_devices(const std::vector<std::string>& dirs, std::vector<std::string>& notes) {
  std::vector<Candidate> out;
  for (const std::string& dir : dirs) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw NetworkFileError(fmt::format("--esi-dir {}: not a directory", dir));
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec)) {
      std::string ext = e.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (e.is_regular_file() && ext == ".xml") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      try {
        for (const esi::EsiDevice& d : esi::read_esi_file(f.string()))
          out.push_back({fmt::format("{}:0x{:08X}:0x{:08X}", fs::absolute(f).lexically_normal().string(), d.product_code,
                                     d.revision),
                         {d.vendor_id, d.product_code, d.revision}});
      } catch (const profile::ProfileError& e) {
        notes.push_back(fmt::format("skipped {}: {}", f.string(), e.what()));
      }
    }
  }
  return out;
}

// The built-in (or --profile-dir) products and their identities.
std::vector<Candidate> builtin_products(const std::string& profile_dir) {
  std::vector<Candidate> out;
  for (const std::string& p : profile::known_products()) {
    const profile::Identity i = profile::load_profile(p, profile_dir).identity;
    out.push_back({p, {i.vendor_id, i.product_code, i.revision}, i.product_code_mask});
  }
  return out;
}

int port_number(const esi::XmlReading& xml, const XMLElement* port) {
  const std::string t = esi::XmlReading::text(port);
  if (t.size() == 1 && t[0] >= 'A' && t[0] <= 'D') return t[0] - 'A';
  if (t.size() == 1 && t[0] >= '0' && t[0] <= '3') return t[0] - '0';
  xml.fail(port, fmt::format("'{}': expected a port A, B, C or D", t));
}

// Where vdrive looked for a device, for messages: the search directories and the files that
// could not be read.
std::string searched(const std::vector<std::string>& esi_dirs, const std::vector<std::string>& notes) {
  std::string dirs;
  for (const std::string& d : esi_dirs) dirs += (dirs.empty() ? "" : ", ") + d;
  std::string skipped;
  for (const std::string& n : notes)
    if (n.rfind("skipped ", 0) == 0) skipped += "\n  " + n;
  return fmt::format("searched {}{}", dirs.empty() ? "no --esi-dir" : dirs,
                     skipped.empty() ? "" : "; files that could not be read:" + skipped);
}

// A slave nothing matches: served from the ENI's own description (esi/eni_slave_device.hpp), named
// FILE.xml#PHYSADDR, with a warning saying what was assumed; refused where the ENI says too little.
esi::ImportedDevice serve_from_eni(const esi::EniSlave& s, const std::string& path, const std::string& who,
                                   const std::string& searched, NetworkSlave& slave, EniNetwork& out) {
  const std::string unmatched = fmt::format("no built-in product and no ESI device matches it ({})", searched);
  if (!s.phys_addr)
    throw NetworkFileError(fmt::format("{}:{}: <Slave>: {}: {}; without a <PhysAddr> it cannot be served from the "
                                       "ENI alone", path, s.line, who, unmatched));
  esi::EniSlaveDevice d;
  esi::ImportedDevice imported;
  try {
    d = esi::eni_slave_device(s);
    imported = esi::import_device(d.device);
  } catch (const profile::ProfileError& e) {
    throw NetworkFileError(fmt::format("{}; {}", e.what(), unmatched));
  }
  slave.device = esi::eni_slave_reference(fs::absolute(path).lexically_normal().string(), *s.phys_addr);
  std::string assumed;
  for (const std::string& a : d.assumptions) assumed += (assumed.empty() ? "" : "; ") + a;
  const std::string note = fmt::format("{}: served from the ENI alone as {}: no ESI for vendor 0x{:08X} product "
                                       "0x{:08X} ({}); assumed: {}", who, slave.device, s.vendor_id, s.product_code,
                                       searched, assumed);
  out.notes.push_back(note);
  out.warnings.push_back(note);
  for (const std::string& c : d.created) {
    out.notes.push_back(fmt::format("{}: {}", who, c));
    out.warnings.push_back(out.notes.back());
  }
  return imported;
}

// The slave's init commands as its device would answer them (eni_init_commands.hpp): each one it
// refuses is a warning.
void check(const esi::EniSlave& s, const NetworkSlave& slave, const std::optional<esi::ImportedDevice>& served_alone,
           const std::string& profile_dir, const std::string& who, EniNetwork& out) {
  if (s.coe_init_commands.empty() && s.init_commands.empty()) return;
  std::vector<std::string> refused;
  if (served_alone) {
    refused = check_init_commands(s, served_alone->profile, *served_alone->dictionary, who);
  } else if (esi::is_esi_reference(slave.device)) {
    const std::shared_ptr<const esi::ImportedDevice> d = esi::load_esi_device(slave.device);
    refused = check_init_commands(s, d->profile, *d->dictionary, who);
  } else {
    const profile::ProductProfile p = profile::load_profile(slave.device, profile_dir);
    refused = check_init_commands(s, p, *od::shared_dictionary(p, profile_dir), who);
  }
  for (std::string& r : refused) {
    out.notes.push_back(r);
    out.warnings.push_back(std::move(r));
  }
}

}  // namespace

EniNetwork read_eni(const std::string& path, const std::vector<std::string>& esi_dirs, const std::string& profile_dir) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw NetworkFileError(fmt::format("{}: cannot read the ENI file", path));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_eni(text.str(), path, esi_dirs, profile_dir);
}

EniNetwork parse_eni(std::string_view s, const std::string& path, const std::vector<std::string>& esi_dirs,
                     const std::string& profile_dir) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(s.data(), s.size()) != tinyxml2::XML_SUCCESS)
    throw NetworkFileError(fmt::format("{}:{}: not well-formed XML: {}", path, doc.ErrorLineNum(),
                                       doc.ErrorStr() != nullptr ? doc.ErrorStr() : "parse error"));
  const esi::XmlReading xml(path);
  EniNetwork out;
  out.network.file = path;
  try {
    const XMLElement* root = doc.RootElement();
    if (root == nullptr || std::string_view(root->Name()) != "EtherCATConfig")
      xml.fail(root, "not an ENI file: the root element is not <EtherCATConfig>");
    const XMLElement* config = xml.required(root, "Config");
    const std::vector<Candidate> builtins = builtin_products(profile_dir);
    const std::vector<Candidate> candidates = esi_devices(esi_dirs, out.notes);
    std::map<std::string, int> names;
    struct Previous {
      const XMLElement* at = nullptr;
      std::uint16_t phys = 0;
      int port = 1;
    };
    std::vector<Previous> previous;
    for (const XMLElement* sl = config->FirstChildElement("Slave"); sl; sl = sl->NextSiblingElement("Slave")) {
      const esi::EniSlave eni_slave = esi::read_eni_slave(xml, sl);
      NetworkSlave slave;
      slave.line = sl->GetLineNum();
      slave.name = eni_slave.name;
      if (slave.name.empty()) slave.name = fmt::format("slave {}", out.network.slaves.size() + 1);
      if (const int seen = names[slave.name]++; seen > 0) slave.name += fmt::format(" ({})", seen + 1);  // unique
      const Identity id{eni_slave.vendor_id, eni_slave.product_code, eni_slave.revision};
      const std::uint16_t phys = eni_slave.phys_addr.value_or(0);
      const std::string who = fmt::format("slave {} '{}' (vendor 0x{:08X}, product 0x{:08X}, revision 0x{:08X})",
                                          out.network.slaves.size() + 1, slave.name, id.vendor, id.product, id.revision);
      std::optional<esi::ImportedDevice> served_alone;
      const auto builtin = std::find_if(builtins.begin(), builtins.end(), [&](const Candidate& c) {
        return c.id.vendor == id.vendor && (c.id.product & c.mask) == (id.product & c.mask);
      });
      if (builtin != builtins.end()) {
        slave.device = builtin->reference;
        const bool same = builtin->id.product == id.product && builtin->id.revision == id.revision;
        // A product of the series the built-in product covers: served with the ENI's identity.
        if (!same) slave.identity = network::IdentityChoice{id.product, id.revision};
        out.notes.push_back(fmt::format("{}: built-in product {}{}", who, builtin->reference,
                                        same ? "" : ", with the ENI's product code and revision"));
      } else {
        const Candidate* exact = nullptr;
        const Candidate* near = nullptr;
        for (const Candidate& c : candidates) {
          if (c.id.vendor != id.vendor || c.id.product != id.product) continue;
          if (c.id.revision == id.revision) exact = exact ? exact : &c;
          if (!near || (c.id.revision > near->id.revision && c.id.revision <= id.revision) ||
              (near->id.revision > id.revision && c.id.revision < near->id.revision))
            near = &c;
        }
        if (exact) {
          slave.device = exact->reference;
          out.notes.push_back(fmt::format("{}: {}", who, exact->reference));
        } else if (near) {
          slave.device = near->reference;
          out.notes.push_back(fmt::format("{}: no ESI with its revision; served as {} (revision 0x{:08X})", who,
                                          near->reference, near->id.revision));
        } else {
          served_alone = serve_from_eni(eni_slave, path, who, searched(esi_dirs, out.notes), slave, out);
        }
      }
      check(eni_slave, slave, served_alone, profile_dir, who, out);
      Previous prev;
      if (const XMLElement* pp = esi::XmlReading::child(sl, "PreviousPort")) {
        // Several <PreviousPort> (redundancy alternatives): the one Selected, else the first.
        for (const XMLElement* p = pp; p; p = p->NextSiblingElement("PreviousPort"))
          if (xml.flag(p, "Selected", false)) pp = p;
        prev.at = pp;
        prev.phys = static_cast<std::uint16_t>(xml.number(xml.required(pp, "PhysAddr"), 0, 0xFFFF));
        prev.port = port_number(xml, xml.required(pp, "Port"));
      }
      previous.push_back(prev);
      out.station_addresses.push_back(phys);
      out.network.slaves.push_back(std::move(slave));
    }
    if (out.network.slaves.empty()) xml.fail(config, "no <Slave>");
    // Topology from PreviousPort; none at all (or only a chain of port B): the line.
    bool line = true;
    for (std::size_t i = 0; i < previous.size(); ++i) {
      const Previous& p = previous[i];
      if (i == 0) line &= p.at == nullptr;
      else line &= p.at != nullptr && p.port == 1 && p.phys == out.station_addresses[i - 1];
    }
    if (!line) {
      out.network.topology.uplinks.resize(previous.size());
      for (std::size_t i = 0; i < previous.size(); ++i) {
        network::Uplink& up = out.network.topology.uplinks[i];
        if (previous[i].at == nullptr) {
          up.parent = i == 0 ? network::Uplink::kMaster : static_cast<int>(i - 1);
          if (i > 0) out.notes.push_back(fmt::format("slave {}: no <PreviousPort>; cabled to port B of the slave before", i + 1));
          continue;
        }
        const auto it = std::find(out.station_addresses.begin(), out.station_addresses.end(), previous[i].phys);
        if (it == out.station_addresses.end())
          xml.fail(previous[i].at, fmt::format("PhysAddr {} is no slave of this ENI", previous[i].phys));
        up.parent = static_cast<int>(it - out.station_addresses.begin());
        up.port = previous[i].port;
      }
    }
  } catch (const profile::ProfileError& e) {  // EsiError from the XML reading
    throw NetworkFileError(e.what());
  }
  return out;
}

std::string to_network_yaml(const NetworkFile& n, const std::vector<std::string>& notes) {
  std::string y = fmt::format("# Network file made by `vdrive network --from-eni` from {}\n", n.file);
  for (const std::string& note : notes) y += "# " + note + "\n";
  y += "slaves:\n";
  auto quoted = [](const std::string& s) {
    std::string q = "\"";
    for (const char c : s) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return q + "\"";
  };
  for (std::size_t i = 0; i < n.slaves.size(); ++i) {
    const NetworkSlave& s = n.slaves[i];
    y += fmt::format("  - {{name: {}, device: {}", quoted(s.name), quoted(s.device));
    if (!n.topology.uplinks.empty()) {
      const network::Uplink& up = n.topology.uplinks[i];
      if (up.parent == network::Uplink::kMaster) y += ", parent: master";
      else y += fmt::format(", parent: {}, port: {}", up.parent + 1, up.port);
    }
    if (s.alias) y += fmt::format(", alias: 0x{:04X}", *s.alias);
    if (s.identity) y += fmt::format(", product_code: 0x{:08X}, revision: 0x{:08X}", s.identity->product_code, s.identity->revision);
    y += "}\n";
  }
  return y;
}

}  // namespace vdrive::machine
