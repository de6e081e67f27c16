#include "vdrive/machine/network_file.hpp"

#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "common/nearest_word.hpp"
#include "common/number_text.hpp"
#include "common/time_text.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/machine/network_file_part.hpp"
#include "vdrive/machine/yaml_fault_source.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::machine {
namespace {

namespace fs = std::filesystem;

class Reader {
public:
  Reader(std::string file, std::string base) : file_(std::move(file)), base_(std::move(base)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& what) const {
    const YAML::Mark m = at.Mark();
    throw NetworkFileError(m.is_null() ? fmt::format("{}: {}", file_, what)
                                       : fmt::format("{}:{}: {}", file_, m.line + 1, what));
  }

  // Keys of `map` must be among `allowed`; a typo gets the nearest key as a suggestion.
  void only_keys(const YAML::Node& map, const std::string& where, const std::vector<std::string>& allowed) const {
    for (const auto& kv : map) {
      const std::string key = kv.first.Scalar();
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      const std::vector<std::string_view> candidates(allowed.begin(), allowed.end());
      const auto best = nearest_word(key, candidates);
      fail(kv.first, fmt::format("{}: unknown key '{}'{} (keys: {})", where, key,
                                 best ? fmt::format(", did you mean '{}'?", *best) : "", join(allowed)));
    }
  }

  std::string path(const std::string& relative) const {
    if (relative.empty() || fs::path(relative).is_absolute()) return relative;
    return (fs::path(base_) / relative).lexically_normal().string();
  }

  const std::string& file() const { return file_; }

private:
  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  std::string file_, base_;
};

std::uint64_t number(const Reader& r, const YAML::Node& n, const std::string& field, std::uint64_t max) {
  if (!n.IsScalar()) r.fail(n, fmt::format("{}: expected a number", field));
  const auto v = parse_unsigned(n.Scalar());
  if (!v) r.fail(n, fmt::format("{}: '{}' is not a number (decimal or 0x hex)", field, n.Scalar()));
  if (*v > max) r.fail(n, fmt::format("{}: {} is above {}", field, n.Scalar(), max));
  return *v;
}

std::string text(const Reader& r, const YAML::Node& n, const std::string& field) {
  if (!n.IsScalar() || n.Scalar().empty()) r.fail(n, fmt::format("{}: expected a non-empty text", field));
  return n.Scalar();
}

// The port descriptor (register 0x0007) of a device, for the topology check.
std::uint8_t port_descriptor(const std::string& device, const std::string& profile_dir) {
  if (esi::is_esi_reference(device)) return esi::load_esi_device(device)->profile.esc.port_descriptor;
  return profile::load_profile(device, profile_dir).esc.port_descriptor;
}

// A slave by name or 1-based position.
std::size_t slave_ref(const Reader& r, const YAML::Node& n, const std::string& field, const NetworkFile& f) {
  const std::string s = text(r, n, field);
  for (std::size_t i = 0; i < f.slaves.size(); ++i)
    if (f.slaves[i].name == s) return i;
  if (const auto v = parse_unsigned(s); v && *v >= 1 && *v <= f.slaves.size()) return static_cast<std::size_t>(*v - 1);
  std::string names;
  for (const NetworkSlave& sl : f.slaves) names += (names.empty() ? "" : ", ") + sl.name;
  r.fail(n, fmt::format("{}: no slave '{}' (names: {}; or a position 1-{})", field, s, names, f.slaves.size()));
}

// "NAME 0x7000:1" or "NAME.home" -> the slave and the entry or plant connection.
network::SignalPoint signal_point(const Reader& r, const YAML::Node& n, const std::string& field, const NetworkFile& f) {
  const std::string s = text(r, n, field);
  std::vector<std::string> names;
  for (const NetworkSlave& sl : f.slaves) names.push_back(sl.name);
  try {
    return network::parse_signal_point(s, names);
  } catch (const std::invalid_argument& e) {
    r.fail(n, fmt::format("{}: {}", field, e.what()));
  }
}

bool is_identifier(const std::string& s) {
  return !s.empty() && !std::isdigit(static_cast<unsigned char>(s[0])) &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; });
}

}  // namespace

NetworkFile parse_network_file(const std::string& text_in, const std::string& file, const std::string& base_dir,
                               const std::string& profile_dir) {
  Reader r(file, base_dir);
  YAML::Node root;
  try {
    root = YAML::Load(text_in);
  } catch (const YAML::Exception& e) {
    throw NetworkFileError(fmt::format("{}:{}: not YAML: {}", file, e.mark.line + 1, e.msg));
  }
  // An empty document (nothing but comments) has no node to carry a line: it is line 1.
  if (!root.IsMap() && root.Mark().is_null())
    throw NetworkFileError(fmt::format("{}:1: no content: expected a mapping with 'slaves' (and 'wires', 'signals')", file));
  if (!root.IsMap()) r.fail(root, "expected a mapping with 'slaves' (and 'wires', 'signals')");
  r.only_keys(root, "(top level)", {"slaves", "wires", "signals", "faults", "processes"});
  const YAML::Node slaves = root["slaves"];
  if (!slaves || !slaves.IsSequence() || slaves.size() == 0) r.fail(root, "slaves: expected a list of at least one slave");

  NetworkFile f;
  f.file = file;
  std::set<std::string> names;
  struct Parent {
    YAML::Node parent, port;
  };
  std::vector<Parent> parents;
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    const YAML::Node s = slaves[i];
    const std::string where = fmt::format("slaves[{}]", i);
    if (!s.IsMap()) r.fail(s, where + ": expected a mapping with 'device'");
    r.only_keys(s, where, {"name", "device", "alias", "plant", "parent", "port", "product_code", "revision"});
    NetworkSlave sl;
    sl.line = s.Mark().line + 1;
    sl.name = s["name"] ? text(r, s["name"], where + ".name") : fmt::format("slave {}", i + 1);
    if (!names.insert(sl.name).second) r.fail(s["name"] ? s["name"] : s, where + ".name: '" + sl.name + "' is used twice");
    if (!s["device"]) r.fail(s, where + ".device: missing (a product id such as a6b, or FILE.xml[:PRODUCT[:REVISION]])");
    sl.device = text(r, s["device"], where + ".device");
    if (esi::is_esi_reference(sl.device)) sl.device = r.path(sl.device);
    try {
      if (esi::is_esi_reference(sl.device)) {
        (void)esi::load_esi_device(sl.device);
      } else {
        (void)profile::load_profile(sl.device, profile_dir);
      }
    } catch (const profile::ProfileError& e) {
      std::string known;
      for (const std::string& id : profile::known_products()) known += (known.empty() ? "" : ", ") + id;
      r.fail(s["device"], fmt::format("{}.device: {}{}", where, e.what(),
                                      esi::is_esi_reference(sl.device) ? "" : fmt::format(" (built-in: {})", known)));
    }
    if (s["revision"] && !s["product_code"]) r.fail(s["revision"], where + ".revision: needs 'product_code'");
    if (s["product_code"]) {
      if (esi::is_esi_reference(sl.device))
        r.fail(s["product_code"], where + ".product_code: an ESI device has the identity of its file; name another device");
      network::IdentityChoice id;
      id.product_code = static_cast<std::uint32_t>(number(r, s["product_code"], where + ".product_code", 0xFFFFFFFF));
      const profile::Identity own = profile::load_profile(sl.device, profile_dir).identity;
      id.revision = s["revision"] ? static_cast<std::uint32_t>(number(r, s["revision"], where + ".revision", 0xFFFFFFFF))
                                  : own.revision;
      if (!own.covers(own.vendor_id, id.product_code))
        r.fail(s["product_code"], fmt::format("{}.product_code: {} covers 0x{:08X} under mask 0x{:08X}, not 0x{:08X}", where,
                                              sl.device, own.product_code, own.product_code_mask, id.product_code));
      sl.identity = id;
    }
    if (s["alias"]) sl.alias = static_cast<std::uint16_t>(number(r, s["alias"], where + ".alias", 0xFFFF));
    if (s["plant"]) sl.plant_file = r.path(text(r, s["plant"], where + ".plant"));
    if (s["port"] && !s["parent"]) r.fail(s["port"], where + ".port: needs 'parent' (the slave whose port it is)");
    parents.push_back({s["parent"], s["port"]});
    f.slaves.push_back(std::move(sl));
  }

  // Parents name slaves given anywhere in the file; without any, the slaves form a line.
  const bool tree = std::any_of(parents.begin(), parents.end(), [](const Parent& p) { return bool(p.parent); });
  if (tree) {
    f.topology.uplinks.resize(f.slaves.size());
    for (std::size_t i = 0; i < f.slaves.size(); ++i) {
      const std::string where = fmt::format("slaves[{}]", i);
      network::Uplink& up = f.topology.uplinks[i];
      if (!parents[i].parent) {
        // Without a parent: the master for the first slave, else port 1 of the slave before.
        up.parent = i == 0 ? network::Uplink::kMaster : static_cast<int>(i - 1);
        up.port = 1;
        continue;
      }
      const std::string p = parents[i].parent.IsScalar() ? parents[i].parent.Scalar() : "";
      up.parent = p == "master" ? network::Uplink::kMaster
                                : static_cast<int>(slave_ref(r, parents[i].parent, where + ".parent", f));
      up.port = parents[i].port ? static_cast<int>(number(r, parents[i].port, where + ".port", 3)) : 1;
    }
    std::vector<std::uint8_t> descriptors;
    for (const NetworkSlave& sl : f.slaves) descriptors.push_back(port_descriptor(sl.device, profile_dir));
    try {
      network::validate(f.topology, descriptors);
    } catch (const std::invalid_argument& e) {
      r.fail(slaves, fmt::format("slaves: {}", e.what()));
    }
  }

  if (const YAML::Node wires = root["wires"]) {
    if (!wires.IsSequence()) r.fail(wires, "wires: expected a list of {from: POINT, to: POINT} (SLAVE INDEX:SUB or SLAVE.CONNECTION)");
    for (std::size_t i = 0; i < wires.size(); ++i) {
      const YAML::Node w = wires[i];
      const std::string where = fmt::format("wires[{}]", i);
      if (!w.IsMap()) r.fail(w, where + ": expected a mapping with 'from' and 'to'");
      r.only_keys(w, where, {"from", "to"});
      if (!w["from"] || !w["to"]) r.fail(w, where + ": needs 'from' and 'to'");
      network::SignalWire sw;
      sw.from = signal_point(r, w["from"], where + ".from", f);
      sw.to = signal_point(r, w["to"], where + ".to", f);
      if (sw.from == sw.to) r.fail(w, where + ": 'from' and 'to' are the same point");
      sw.name = fmt::format("{}:{}: {} ({} -> {})", file, w.Mark().line + 1, where, w["from"].Scalar(), w["to"].Scalar());
      f.wires.push_back(std::move(sw));
    }
  }

  if (const YAML::Node signals = root["signals"]) {
    if (!signals.IsMap()) r.fail(signals, "signals: expected a mapping NAME: POINT (SLAVE INDEX:SUB or SLAVE.CONNECTION)");
    for (const auto& kv : signals) {
      const std::string name = kv.first.Scalar();
      if (!is_identifier(name))
        r.fail(kv.first, fmt::format("signals: '{}' is not a signal name (letters, digits, '_' and '-', not starting with a digit)", name));
      for (const network::NamedSignal& other : f.signals)
        if (other.name == name) r.fail(kv.first, fmt::format("signals: '{}' is given twice", name));
      network::NamedSignal sig;
      sig.name = name;
      sig.point = signal_point(r, kv.second, "signals." + name, f);
      sig.origin = fmt::format("{}:{}", file, kv.first.Mark().line + 1);
      f.signals.push_back(std::move(sig));
    }
  }

  if (const YAML::Node faults = root["faults"]) {
    if (!faults.IsSequence()) r.fail(faults, "faults: expected a list of {kind: KIND, ...} (docs/faults.md)");
    std::vector<std::string> names;
    for (const NetworkSlave& sl : f.slaves) names.push_back(sl.name);
    for (std::size_t i = 0; i < faults.size(); ++i) {
      const YAML::Node n = faults[i];
      const std::string where = fmt::format("faults[{}]", i);
      if (!n.IsMap()) r.fail(n, where + ": expected a mapping with 'kind' and the kind's fields (docs/faults.md)");
      ArmedFault a;
      a.spec = read_yaml_fault(n, file, where, names, {"at"});
      if (n["at"]) {
        const auto t = n["at"].IsScalar() ? parse_time(n["at"].Scalar()) : std::nullopt;
        if (!t) r.fail(n["at"], where + ".at: expected a time with a unit (e.g. 5s, 250ms)");
        a.at = *t;
      }
      a.origin = fmt::format("{}:{}", file, n.Mark().line + 1);
      f.faults.push_back(std::move(a));
    }
  }
  if (const YAML::Node processes = root["processes"]) {
    f.processes = static_cast<std::size_t>(number(r, processes, "processes", 64));
    if (f.processes == 0 || f.processes > f.slaves.size())
      r.fail(processes, fmt::format("processes: {} parts for {} slave(s); give 1 to {}", f.processes, f.slaves.size(),
                                    std::min<std::size_t>(f.slaves.size(), 64)));
    check_cut(f, network::split_line(f.slaves.size(), f.processes));
  }
  return f;
}

network::NetworkOptions network_options(const NetworkFile& file) {
  network::NetworkOptions o;
  for (const NetworkSlave& s : file.slaves) {
    o.station_aliases.push_back(s.alias);
    o.identities.push_back(s.identity);
    o.slave_names.push_back(s.name);
  }
  o.topology = file.topology;
  o.wires = file.wires;
  o.signals = file.signals;
  return o;
}

NetworkFile load_network_file(const std::string& path, const std::string& profile_dir) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw NetworkFileError(fmt::format("{}: cannot read the network file", path));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_network_file(text.str(), path, fs::path(path).parent_path().string(), profile_dir);
}

}  // namespace vdrive::machine
