#pragma once
// A network file (YAML): the one place a bench is described. The slaves in cable order, each a
// built-in product or an ESI device, with its name, station alias, plant and place in the
// topology (which port of which slave its port 0 is cabled to), the wires between signal points
// (slaves' entries and drives' plant connections), names for signal points, and faults to arm. `vdrive run --network FILE` serves it; docs/networks.md has the format:
//
//   slaves:
//     - {name: coupler, device: io_terminals.xml:0x044c2c52}
//     - {name: di, device: io_terminals.xml:0x03f03052, alias: 7}
//     - {name: x, device: a6b, plant: x.yaml, parent: coupler, port: 3}
//   wires:
//     - {from: do 0x7000:1, to: di 0x6000:1}
//     - {from: do 0x7000:2, to: x.probe1}          # a plant connection (network/signal_point.hpp)
//   signals:
//     door: di 0x6000:2                             # named for the control socket, scenarios, DDS
//   faults:
//     - {kind: link_down, slave: coupler, port: 1, at: 5s, duration: 200ms}
//   processes: 2                                    # a line cut into parts (network_file_part.hpp)
//
// Paths (ESI files, plants) are relative to the network file. Every mistake is a
// NetworkFileError "<file>:<line>: <field>: <what>".
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/fault/fault_spec.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::machine {

class NetworkFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct NetworkSlave {
  std::string name;                       // as the file names it ("slave N" when it does not)
  std::string device;                     // product id or ESI reference (path resolved)
  std::optional<std::uint16_t> alias;
  // A built-in product served with another identity it covers (product_code, revision keys).
  std::optional<network::IdentityChoice> identity;
  std::string plant_file;                 // resolved path, "" = the product's default plant
  int line = 0;                           // 1-based, for messages
};

// A fault the file arms: injected `at` after the network starts serving (docs/faults.md kinds and
// fields; `slave` by name or position).
struct ArmedFault {
  fault::FaultSpec spec;
  Nanos at = 0;
  std::string origin;                     // "bench.yaml:21", for logs
};

struct NetworkFile {
  std::string file;
  std::vector<NetworkSlave> slaves;
  network::Topology topology;             // empty: the line
  std::vector<network::SignalWire> wires;
  std::vector<network::NamedSignal> signals;
  std::vector<ArmedFault> faults;
  // `processes: N`: the line served in N processes, as `vdrive run --processes N` (0: not given).
  std::size_t processes = 0;
};

// The file's aliases, identities, topology, wires, signals and slave names as network options
// (plants are the caller's: it reads them as its other plant files).
network::NetworkOptions network_options(const NetworkFile& file);

// Reads and checks the file: names unique, devices known (built-in, --profile-dir or an ESI file
// that reads), parents and ports possible (network::validate), wire ends naming slaves.
NetworkFile load_network_file(const std::string& path, const std::string& profile_dir = {});
// The same for text in memory; `file` names it and paths are relative to `base_dir`.
NetworkFile parse_network_file(const std::string& text, const std::string& file, const std::string& base_dir,
                               const std::string& profile_dir = {});

}  // namespace vdrive::machine
