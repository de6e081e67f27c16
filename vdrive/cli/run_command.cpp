#include "vdrive/cli/run_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "ethercat/slave_ref.hpp"
#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/run_status.hpp"
#include "vdrive/cli/telemetry_command.hpp"
#include "vdrive/cli/web_option.hpp"
#include "vdrive/telemetry/loop_services.hpp"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/control/control_socket.hpp"
#include "vdrive/control/fault_service.hpp"
#include "vdrive/control/part_router.hpp"
#include "vdrive/drive/product_plant.hpp"
#include "vdrive/fault/impaired_link.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/link/net_namespace.hpp"
#include "vdrive/link/raw_socket_link.hpp"
#include "vdrive/link/tap_link.hpp"
#include "plant/plant.hpp"
#include "plant/plant_yaml.hpp"
#include "vdrive/network/line_parts.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/machine/eni_reader.hpp"
#include "vdrive/machine/network_file.hpp"
#include "vdrive/machine/network_file_part.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/runtime/loop_waker.hpp"
#include "vdrive/runtime/cpu_affinity.hpp"
#include "vdrive/cli/part_processes.hpp"
#include "vdrive/runtime/onward_link.hpp"
#include "vdrive/runtime/time_slice.hpp"
#include "vdrive/runtime/realtime.hpp"
#include "vdrive/runtime/stop_signal.hpp"

namespace vdrive::cli {
namespace {

// How part 1 of --processes gives the later parts the token their pages ask of a change.
constexpr const char* kPartWebTokenVariable = "VDRIVE_PART_WEB_TOKEN";

struct RunOptions {
  std::string iface;
  std::string tap;
  std::string next_iface;           // --next-iface: the line goes on out of the last slave's port 1 there
  std::string netns;                // --netns: the interfaces are in this network namespace
  long processes = 1;               // --processes: the line cut into N parts, one process and core each
  bool processes_given = false;     // --processes on the command line (else a network file's `processes:`)
  std::string line_part;            // --line-part FIRST:COUNT: a part of --processes serves these of the file's slaves
  bool network_loaded = false;      // `network` and `drives` hold the network file or ENI already
  int ready_fd = -1;                // a part of --processes tells its parent here that it serves
  std::size_t later_slaves = 0;     // --processes, part 1: the slaves the other parts serve
  std::size_t slaves_before = 0;    // --slaves-before: a later part of --processes, the slaves ahead of it
  std::size_t run_part = 1;         // --run-part K, --run-parts N: which part of --processes this is
  std::size_t run_parts = 1;
  Nanos clock_origin = 0;           // --clock-origin: a part of --processes times from part 1's epoch (0: its own)
  std::vector<control::RemotePart> later_parts;  // --processes, part 1: their control sockets
  bool part_page = false;                        // --part-page: a later part's page, on a loopback port of its own
  std::vector<web::PartPage> later_pages;        // --processes with --web, part 1: their pages
  std::string later_pages_token;                 // what their pages ask of a change
  std::vector<std::string> drives;
  std::string network_file;         // --network: the slaves, topology, aliases and wires of a network file
  std::string eni;                  // --eni: the network a master's ENI describes
  std::vector<std::string> esi_dirs;  // --esi-dir: where the ENI's devices' ESI files are
  Nanos hop_delay = 500;
  std::string profile_dir;
  bool no_qdisc_bypass = false;
  bool foe_strict = false;          // --foe-strict: FoE takes only ECATFW__ files in vdrive's image format
  int rt_priority = 0;  // 0: normal scheduling
  long busy_poll_us = 0;  // raw socket: spin before sleeping (RawSocketLink::Options::busy_poll)
  long batch_steps_us = 0;  // the drives' control steps wait this long for a wake-up (Network::set_control_step_batch)
  bool no_rx_ring = false;  // raw socket: recvfrom instead of the PACKET_RX_RING (RawSocketLink::Options::rx_ring)
  int cpu = -1;           // pin the serving thread; -1: no pinning
  long slice_us = 100;    // the serving thread's time slice (runtime::set_time_slice); 0: the kernel's
  bool slice_given = false;  // --slice-us on the command line or in the config: failing to set it is an error
  std::vector<std::string> plants;  // "N:FILE": slave N (cable order, 1 = first) moves the plant in FILE
  std::string control;              // runtime control socket; empty: default_control_path()
  std::uint64_t fault_seed = 1;     // wire impairment's generator
  bool no_control = false;
  StatusMode status = StatusMode::automatic;  // --status / --no-status
  double stall_ms = 1.0;  // --stall-threshold-ms: the floor of the host-stall threshold (run_status.hpp)
  RunTelemetryOptions telemetry;   // --telemetry: DDS telemetry (docs/telemetry.md)
  std::string web;                 // --web [ADDR:]PORT: the live page (docs/web.md)
  machine::NetworkFile network;    // read from network_file
};

// Runtime control: a request line from the socket's thread -> the loop -> a reply line.
std::string answer(control::FaultService& service, std::string_view line) {
  control::ControlReply reply;
  try {
    const control::ControlRequest request = control::parse_request(line);
    reply = service.call(request, 2'000'000'000);  // the service logs what it did, whoever asked
  } catch (const control::ProtocolError& e) {
    reply = control::error_reply(control::ControlReply::Status::bad_request, e.what());
  }
  if (!reply.ok()) spdlog::warn("control request refused: {}", reply.error);
  return control::format_reply(reply);
}

std::string control_path(const RunOptions& o) {
  return o.control.empty() ? control::default_control_path(o.tap.empty() ? o.iface : o.tap) : o.control;
}

// --processes: part K's (from 2) private control socket beside part 1's: /run/vdrive/eth1.sock ->
// /run/vdrive/eth1.part2.sock. Part 1's socket stays the run's one address (part_router.hpp).
std::string part_control_path(const std::string& path, std::size_t part) {
  constexpr std::string_view kSuffix = ".sock";
  const bool sock = path.size() > kSuffix.size() && path.ends_with(kSuffix);
  return fmt::format("{}.part{}{}", sock ? path.substr(0, path.size() - kSuffix.size()) : path, part, sock ? kSuffix : "");
}

// Part 1 of --processes: the router in front of every part's faults (part_router.hpp), for the
// control socket and the telemetry's requests alike; null for a process that is the whole line.
std::shared_ptr<control::PartRouter> part_router(const RunOptions& o, control::FaultService& service) {
  if (o.later_parts.empty()) return nullptr;
  return std::make_shared<control::PartRouter>(
      o.drives.size(), o.later_parts, [&service](const control::ControlRequest& r) { return service.call(r, 2'000'000'000); },
      [](const std::string& to, std::string_view line, Nanos timeout) { return control::control_call(to, line, timeout); });
}

std::unique_ptr<control::ControlServer> open_control(const RunOptions& o, control::FaultService& service,
                                                     const std::shared_ptr<control::PartRouter>& router) {
  const std::string path = control_path(o);
  control::ControlServer::Handler handler = [&service](std::string_view line) { return answer(service, line); };
  // Requests for the other parts' slaves go on to their sockets, on the socket's thread.
  if (router) handler = [router](std::string_view line) { return router->answer(line); };
  try {
    return std::make_unique<control::ControlServer>(
        path, std::move(handler),
        [](unsigned uid) {
          return control::format_reply(control::error_reply(
              control::ControlReply::Status::denied, fmt::format("uid {} may not control this vdrive (only uid {} or root)", uid, ::geteuid())));
        });
  } catch (const control::ControlSocketError& e) {
    throw CliError(e.kind() == control::ControlSocketError::Kind::not_permitted ? kExitNotPermitted : kExitFailure,
                   fmt::format("--control: {}", e.what()));
  }
}

// N of --plant N:FILE as an index (0-based): the position from 1, as every command counts. A
// station address is the master's to set at run time, so it names no slave here.
std::size_t plant_slave(const std::string& arg, std::size_t slaves) {
  const std::size_t colon = arg.find(':');
  if (colon == std::string::npos || colon == 0)
    throw CliError(kExitBadArguments, fmt::format("--plant '{}': expected N:FILE (N = the slave's position, 1 = first)", arg));
  ecat::SlaveRef ref;
  try {
    ref = ecat::parse_slave_ref(arg.substr(0, colon));
  } catch (const std::invalid_argument& e) {
    throw CliError(kExitBadArguments, fmt::format("--plant '{}': {}", arg, e.what()));
  }
  if (ref.is_address())
    throw CliError(kExitBadArguments, fmt::format("--plant '{}': a station address is set by the master when it runs; "
                                                  "give the slave's position (1 = first)", arg));
  if (ref.value > slaves)
    throw CliError(kExitBadArguments, fmt::format("--plant '{}': there are {} drives (positions 1-{})", arg, slaves, slaves));
  return ref.value - 1u;
}

// --plant N:FILE -> per-slave plant descriptions. Errors name the option, the value and, for a bad
// file, the file, line and field (plant_yaml.hpp).
std::vector<std::optional<plant::PlantDescription>> load_plants(const RunOptions& o) {
  std::vector<std::optional<plant::PlantDescription>> plants(o.drives.size());
  for (const std::string& arg : o.plants) {
    const std::size_t colon = arg.find(':');
    const std::size_t slave = plant_slave(arg, o.drives.size());
    if (plants[slave]) throw CliError(kExitBadArguments, fmt::format("--plant '{}': slave {} already has a plant", arg, slave + 1));
    try {
      plant::PlantDescription d = plant::load_plant_file(arg.substr(colon + 1), [&](std::string_view id) -> std::optional<plant::MotorCatalogue> {
        try {
          return drive::motor_catalogue(profile::load_profile(id, o.profile_dir));
        } catch (const profile::ProfileError&) {
          return std::nullopt;
        }
      });
      if (d.axes.empty()) throw CliError(kExitBadArguments, fmt::format("--plant '{}': the plant has no axis for the drive", arg));
      plants[slave] = std::move(d);
    } catch (const plant::PlantYamlError& e) {
      throw CliError(kExitBadArguments, fmt::format("--plant: {}", e.what()));
    } catch (const plant::PlantError& e) {
      throw CliError(kExitBadArguments, fmt::format("--plant: {}", e.what()));
    }
  }
  return plants;
}

void check_products(const RunOptions& o) {
  const std::vector<std::string> known = profile::known_products();
  for (const std::string& id : o.drives) {
    if (esi::is_esi_reference(id)) {
      try {
        (void)esi::load_esi_device(id);  // read once here, so a broken file is the user's error
      } catch (const profile::ProfileError& e) {
        throw CliError(kExitBadArguments, fmt::format("--drive: {}", e.what()));
      }
      continue;
    }
    if (std::find(known.begin(), known.end(), id) == known.end() && o.profile_dir.empty()) {
      throw CliError(kExitBadArguments,
                     fmt::format("--drive: unknown product '{}' (known: {}; or an ESI device, FILE.xml[:PRODUCT[:REVISION]])",
                                 id, known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
    }
  }
}

int exit_code_for(link::LinkError::Kind kind) {
  switch (kind) {
    case link::LinkError::Kind::NoInterface:
    case link::LinkError::Kind::InterfaceDown: return kExitNoInterface;
    case link::LinkError::Kind::NotPermitted: return kExitNotPermitted;
    case link::LinkError::Kind::BadName: return kExitBadArguments;
    case link::LinkError::Kind::System: break;
  }
  return kExitFailure;
}

// The serving thread's slice: asked for by default, where the kernel has it (SCHED_FIFO needs none).
void apply_time_slice(const RunOptions& o) {
  if (o.slice_us == 0 || (o.rt_priority != 0 && !o.slice_given)) return;
  const int err = runtime::set_time_slice(o.slice_us * 1000);
  if (err == 0) return;
  const std::string why = err == ENOTSUP ? "this kernel keeps no time slice of a thread's own (Linux 6.12 or later does)"
                                         : std::strerror(err);
  if (o.slice_given) throw CliError(kExitFailure, fmt::format("--slice-us {}: {}", o.slice_us, why));
  spdlog::info("serving with the kernel's time slice: {}", why);
}

link::RawSocketLink::Options raw_socket_options(const RunOptions& o) {
  link::RawSocketLink::Options options;
  options.qdisc_bypass = !o.no_qdisc_bypass;
  options.busy_poll = static_cast<Nanos>(o.busy_poll_us) * 1000;
  options.rx_ring = !o.no_rx_ring;
  return options;
}

std::unique_ptr<link::Link> open_link(const RunOptions& o) {
  try {
    if (!o.tap.empty()) return std::make_unique<link::TapLink>(o.tap);
    return std::make_unique<link::RawSocketLink>(o.iface, raw_socket_options(o));
  } catch (const link::LinkError& e) {
    throw CliError(exit_code_for(e.kind()), e.what());
  }
}

// --netns: the calling thread inside the namespace while it opens the interfaces; none without.
std::unique_ptr<link::NetnsScope> enter_netns(const RunOptions& o) {
  if (o.netns.empty()) return nullptr;
  try {
    return std::make_unique<link::NetnsScope>(o.netns);
  } catch (const link::LinkError& e) {
    throw CliError(exit_code_for(e.kind()), fmt::format("--netns: {}", e.what()));
  }
}

// --next-iface: the onward port's interface, and the last slave's port 1 made the onward port.
std::unique_ptr<link::Link> open_onward(const RunOptions& o, network::Network& network) {
  if (o.next_iface.empty()) return nullptr;
  try {
    network.segment().set_onward_port();
  } catch (const std::invalid_argument& e) {
    throw CliError(kExitBadArguments, fmt::format("--next-iface: {}", e.what()));
  }
  try {
    link::RawSocketLink::Options options = raw_socket_options(o);
    options.busy_poll = 0;  // the master's link spins, if asked; the onward link is polled beside it
    return std::make_unique<link::RawSocketLink>(o.next_iface, options);
  } catch (const link::LinkError& e) {
    throw CliError(exit_code_for(e.kind()), fmt::format("--next-iface: {}", e.what()));
  }
}

// The rest of a network file: per-slave plants (read as --plant reads them), station aliases,
// identities, names, topology, wires and signals.
void apply_network_file(const RunOptions& o, network::NetworkOptions& options) {
  const machine::NetworkFile& f = o.network;
  const network::NetworkOptions from_file = machine::network_options(f);
  options.station_aliases = from_file.station_aliases;
  options.identities = from_file.identities;
  options.slave_names = from_file.slave_names;
  options.topology = from_file.topology;
  options.wires = from_file.wires;
  options.signals = from_file.signals;
  options.plants.assign(f.slaves.size(), std::nullopt);
  for (std::size_t i = 0; i < f.slaves.size(); ++i) {
    const machine::NetworkSlave& s = f.slaves[i];
    if (s.plant_file.empty()) continue;
    RunOptions one = o;
    one.plants = {fmt::format("{}:{}", i + 1, s.plant_file)};
    options.plants[i] = load_plants(one)[i];
  }
}

void run(RunOptions o);

// --line-part FIRST:COUNT (a child of --processes over a network file or ENI): only those slaves.
void cut_to_part(RunOptions& o) {
  unsigned long first = 0, count = 0;
  char end = 0;
  if (std::sscanf(o.line_part.c_str(), "%lu:%lu%c", &first, &count, &end) != 2 || count == 0 ||
      first + count > o.network.slaves.size())
    throw CliError(kExitBadArguments, fmt::format("--line-part {}: expected FIRST:COUNT within the {} slaves of {}",
                                                  o.line_part, o.network.slaves.size(), o.network_file));
  o.network = machine::line_part(o.network, {first, count});
  o.drives.clear();
  for (const machine::NetworkSlave& sl : o.network.slaves) o.drives.push_back(sl.device);
}

// --plant N:FILE of the whole line, for the part holding slave N, renumbered within it.
std::vector<std::string> plants_of_part(const std::vector<std::string>& plants, const std::vector<network::LinePart>& parts,
                                        std::size_t part, std::size_t slaves) {
  std::vector<std::string> out;
  for (const std::string& arg : plants) {
    const std::size_t slave = plant_slave(arg, slaves);
    if (network::part_of(parts, slave) != part) continue;
    out.push_back(fmt::format("{}:{}", slave - parts[part].first + 1, arg.substr(arg.find(':') + 1)));
  }
  return out;
}

// --processes N: parts 2..N in child processes chained over veth pairs, part 1 served here.
void run_in_parts(RunOptions o) {
  if (o.drives.empty()) throw CliError(kExitBadArguments, "no slaves: give --drive (repeat)");
  check_products(o);
  (void)load_plants(o);  // every plant file checked, positions as the user counts them
  std::vector<network::LinePart> parts;
  try {
    parts = network::split_line(o.drives.size(), static_cast<std::size_t>(o.processes));
  } catch (const std::invalid_argument& e) {
    throw CliError(kExitBadArguments, fmt::format("--processes {}: {}", o.processes, e.what()));
  }
  const bool from_file = o.network_loaded;
  if (from_file) {
    try {
      machine::check_cut(o.network, parts);
    } catch (const machine::NetworkFileError& e) {
      throw CliError(kExitBadArguments, fmt::format("--processes {}: {}", o.processes, e.what()));
    }
  }
  // Each later part's private control socket beside part 1's (part_router.hpp); none without control.
  std::vector<std::string> sockets(o.no_control ? 0 : parts.size());
  for (std::size_t k = 1; k < sockets.size(); ++k) sockets[k] = part_control_path(control_path(o), k + 1);
  const unsigned cpus = std::max(1U, std::thread::hardware_concurrency());
  const int base_cpu = o.cpu >= 0 ? o.cpu : 0;
  const auto cpu_of = [&](std::size_t k) { return static_cast<int>((static_cast<unsigned>(base_cpu) + k) % cpus); };
  const std::string level(spdlog::level::to_string_view(spdlog::get_level()).data());
  // One time base for the run: the parts' telemetry and logs put their events on one axis.
  const Nanos origin = MonotonicClock().origin();
  const auto child_args = [&](std::size_t k, const std::string& in, const std::string& next) {
    std::vector<std::string> a{"run", "--iface", in};
    const std::string onward = k + 1 < parts.size() ? next : o.next_iface;
    if (!onward.empty()) a.insert(a.end(), {"--next-iface", onward});
    if (from_file) {
      // The child reads the file itself and serves its part of it (the network's paths stay valid).
      if (!o.eni.empty()) {
        a.insert(a.end(), {"--eni", o.eni});
        for (const std::string& dir : o.esi_dirs) a.insert(a.end(), {"--esi-dir", dir});
      } else {
        a.insert(a.end(), {"--network", o.network_file});
      }
      a.insert(a.end(), {"--line-part", fmt::format("{}:{}", parts[k].first, parts[k].count), "--processes", "1"});
    } else {
      a.push_back("--drive");
      for (std::size_t i = parts[k].first; i < parts[k].first + parts[k].count; ++i) a.push_back(o.drives[i]);
      for (const std::string& plant : plants_of_part(o.plants, parts, k, o.drives.size())) a.insert(a.end(), {"--plant", plant});
    }
    if (!o.netns.empty()) a.insert(a.end(), {"--netns", o.netns});
    // Its own page on a loopback port it picks, which part 1's page reads and forwards to.
    if (!o.web.empty()) a.push_back("--part-page");
    a.insert(a.end(), {"--clock-origin", std::to_string(origin), "--slaves-before", std::to_string(parts[k].first),
                       "--run-part", std::to_string(k + 1), "--run-parts", std::to_string(parts.size())});
    // Each part publishes its own slaves' telemetry in the run's domain; part 1 takes the requests.
    if (o.telemetry.enabled)
      a.insert(a.end(), {"--telemetry", "--telemetry-rate", fmt::format("{}", o.telemetry.rate_hz), "--domain",
                         std::to_string(telemetry_domain(o.telemetry.domain))});
    a.insert(a.end(), {"--hop-delay", std::to_string(o.hop_delay), "--cpu", std::to_string(cpu_of(k)), "--fault-seed",
                       std::to_string(o.fault_seed), "--no-status", "--log-level", level});
    // Its own control socket, which part 1's routes to (part_router.hpp); none if part 1 has none.
    if (o.no_control) a.push_back("--no-control");
    else a.insert(a.end(), {"--control", sockets[k]});
    if (!o.profile_dir.empty()) a.insert(a.end(), {"--profile-dir", o.profile_dir});
    if (o.foe_strict) a.push_back("--foe-strict");
    if (o.rt_priority != 0) a.insert(a.end(), {"--rt-priority", std::to_string(o.rt_priority)});
    if (o.slice_given) a.insert(a.end(), {"--slice-us", std::to_string(o.slice_us)});
    if (o.busy_poll_us != 0) a.insert(a.end(), {"--busy-poll-us", std::to_string(o.busy_poll_us)});
    if (o.batch_steps_us != 0) a.insert(a.end(), {"--batch-steps-us", std::to_string(o.batch_steps_us)});
    if (o.no_rx_ring) a.push_back("--no-rx-ring");
    if (o.no_qdisc_bypass) a.push_back("--no-qdisc-bypass");
    a.insert(a.end(), {"--stall-threshold-ms", fmt::format("{}", o.stall_ms)});
    return a;
  };
  // A part killed before it could remove its control socket leaves the file behind; once every
  // part has ended (this outlives `others`), what nobody listens on is removed.
  struct PartSockets {
    const std::vector<std::string>& paths;
    ~PartSockets() {
      for (std::size_t k = 1; k < paths.size(); ++k) control::remove_if_stale(paths[k]);
    }
  } part_sockets{sockets};
  // The parts' pages take changes from part 1's page alone: the token reaches them in their
  // environment (not their command line, which every user can read).
  const std::string page_token = o.web.empty() ? std::string{} : web::new_token();
  if (!page_token.empty()) ::setenv(kPartWebTokenVariable, page_token.c_str(), 1);
  PartProcesses others(parts, fmt::format("vd{}p", ::getpid() % 100000), o.netns, child_args);
  ::unsetenv(kPartWebTokenVariable);
  RunOptions first = o;
  first.processes = 1;
  first.drives.assign(o.drives.begin(), o.drives.begin() + static_cast<long>(parts[0].count));
  first.plants = plants_of_part(o.plants, parts, 0, o.drives.size());
  if (from_file) first.network = machine::line_part(o.network, parts[0]);
  first.next_iface = others.first_onward();
  first.later_slaves = o.drives.size() - parts[0].count;
  for (std::size_t k = 1; k < sockets.size(); ++k) first.later_parts.push_back({parts[k].first, parts[k].count, sockets[k]});
  if (!o.web.empty()) {
    for (std::size_t k = 1; k < parts.size(); ++k) first.later_pages.push_back({parts[k].first, parts[k].count, others.web_port(k)});
    first.later_pages_token = page_token;
  }
  first.cpu = cpu_of(0);
  first.run_parts = parts.size();
  first.clock_origin = origin;
  spdlog::info("the line of {} slaves in {} processes: part 1 (slaves 1-{}) here on CPU {}", o.drives.size(),
               parts.size(), parts[0].count, first.cpu);
  run(first);
  if (const std::vector<std::string> ended = others.ended_early(); !ended.empty())
    throw CliError(kExitFailure, fmt::format("{}", fmt::join(ended, "; ")));
}

void run(RunOptions o) {
  if (!o.next_iface.empty() && (o.next_iface == o.iface || o.next_iface == o.tap))
    throw CliError(kExitBadArguments, fmt::format("--next-iface {}: the master is on that interface already", o.next_iface));
  if (!o.network_file.empty() && !o.network_loaded) {
    if (!o.plants.empty()) throw CliError(kExitBadArguments, "--plant: with --network, a slave's plant is in the network file");
    try {
      o.network = machine::load_network_file(o.network_file, o.profile_dir);
    } catch (const machine::NetworkFileError& e) {
      throw CliError(kExitBadArguments, e.what());
    }
    for (const machine::NetworkSlave& s : o.network.slaves) o.drives.push_back(s.device);
  }
  if (!o.eni.empty() && !o.network_loaded) {
    if (!o.plants.empty()) throw CliError(kExitBadArguments, "--plant: with --eni, write the network file (vdrive network --from-eni) and give plants there");
    try {
      machine::EniNetwork eni = machine::read_eni(o.eni, o.esi_dirs, o.profile_dir);
      for (const std::string& note : eni.notes)
        if (std::find(eni.warnings.begin(), eni.warnings.end(), note) == eni.warnings.end()) spdlog::info("{}", note);
      for (const std::string& warning : eni.warnings) spdlog::warn("{}", warning);
      o.network = std::move(eni.network);
    } catch (const machine::NetworkFileError& e) {
      throw CliError(kExitBadArguments, e.what());
    }
    for (const machine::NetworkSlave& s : o.network.slaves) o.drives.push_back(s.device);
    o.network_file = o.eni;  // the rest as for a network file
  }
  if (!o.line_part.empty() && o.network_file.empty())
    throw CliError(kExitBadArguments, "--line-part: a part of a --network or --eni file; give one");
  if (!o.network_file.empty()) {
    o.network_loaded = true;
    if (o.network.processes != 0 && !o.processes_given) o.processes = static_cast<long>(o.network.processes);
    if (!o.line_part.empty()) cut_to_part(o);
  }
  if (o.processes > 1) {
    run_in_parts(std::move(o));
    return;
  }
  if (o.drives.empty()) throw CliError(kExitBadArguments, "no slaves: give --drive (repeat), --network FILE or --eni FILE");
  check_products(o);
  if (o.cpu >= 0 && !runtime::cpu_is_allowed(o.cpu))
    throw CliError(kExitBadArguments, fmt::format("--cpu {}: no such CPU, or not one this process may use", o.cpu));
  // Logs go to stderr at --log-level (set up by main for every command, log_level.hpp).
  std::vector<std::optional<plant::PlantDescription>> plants = load_plants(o);  // a bad one before the link opens

  std::unique_ptr<link::Link> link;
  {
    const std::unique_ptr<link::NetnsScope> inside = enter_netns(o);
    link = open_link(o);
  }
  const std::string where = (o.tap.empty() ? o.iface : "TAP " + o.tap) + (o.netns.empty() ? "" : " in namespace " + o.netns);

  const MonotonicClock clock = o.clock_origin != 0 ? MonotonicClock(o.clock_origin) : MonotonicClock();
  std::unique_ptr<network::Network> network;
  try {
    network::NetworkOptions options{o.hop_delay, o.profile_dir};
    options.foe_strict_firmware_check = o.foe_strict;
    options.plants = std::move(plants);
    if (!o.network_file.empty()) apply_network_file(o, options);
    network = std::make_unique<network::Network>(o.drives, clock, options);
    network->set_control_step_batch(static_cast<Nanos>(o.batch_steps_us) * 1000);
  } catch (const std::invalid_argument& e) {
    throw CliError(kExitBadArguments, fmt::format("{}", e.what()));
  } catch (const profile::ProfileError& e) {
    // With --profile-dir an unknown id is the user's mistake; otherwise the build is broken.
    throw CliError(o.profile_dir.empty() ? kExitFailure : kExitBadArguments, e.what());
  }

  std::unique_ptr<link::Link> onward_link;
  {
    const std::unique_ptr<link::NetnsScope> inside = enter_netns(o);
    onward_link = open_onward(o, *network);
  }

  // Runtime fault control: a bad-cable stage around the link (one branch while clean) and the
  // control socket, whose requests the loop picks up between frames.
  fault::WireImpairment wire(o.fault_seed);
  fault::ImpairedLink impaired(*link, wire, *network, clock);
  control::FaultService faults(*network, &wire, &impaired);
  const runtime::LoopWaker waker;  // this thread serves: requests cut its wait short
  faults.set_wake([&waker] { waker.wake(); });
  faults.set_later_slaves(o.later_slaves);
  const std::shared_ptr<control::PartRouter> router = o.no_control ? nullptr : part_router(o, faults);
  const std::unique_ptr<control::ControlServer> control = o.no_control ? nullptr : open_control(o, faults, router);
  for (const machine::ArmedFault& a : o.network.faults) faults.arm(a.spec, clock.now() + a.at, a.origin);

  std::atomic<bool>& stop = runtime::stop_on_termination_signals();
  if (onward_link)
    spdlog::info("the line goes on through {} (port 1 of slave {}; link {})", o.next_iface,
                 network->segment().onward_slave() + 1, onward_link->carrier() ? "up" : "down: the line ends here until it comes up");
  if (control) spdlog::info("fault control on {}", control->path());
  for (std::size_t k = 0; control && k < o.later_parts.size(); ++k) {
    const control::RemotePart& p = o.later_parts[k];
    spdlog::info("faults for part {} ({}) go on to its control socket {}", k + 2,
                 p.count == 1 ? fmt::format("slave {}", p.first + 1) : fmt::format("slaves {}-{}", p.first + 1, p.first + p.count),
                 p.socket);
  }
  runtime::LoopCounters counters;
  counters.stalls.set_floor(static_cast<Nanos>(o.stall_ms * 1e6));
  RunStatus status(o.status, *network, counters, &wire);  // the live status line (run_status.hpp)
  status.set_slaves_before(o.slaves_before);
  if (control) status.set_later_parts(o.later_parts);
  // In a line over processes each part publishes its slaves under whole-line positions; part 1
  // takes the requests and routes their faults as its control socket does.
  o.telemetry.place = {o.slaves_before, o.run_part - 1, o.run_parts, o.later_slaves};
  o.telemetry.requests.take_requests = o.run_part == 1;
  if (router)
    o.telemetry.requests.route = [router](const control::ControlRequest& r, std::string_view line) { return router->route(r, line); };
  const std::unique_ptr<telemetry::LineTelemetry> telemetry =
      start_run_telemetry(o.telemetry, *network, impaired, clock, counters, &faults, [&waker] { waker.wake(); });
  web::WebServerOptions page_options;
  if (o.run_parts > 1) {
    page_options.origin = 0;  // the run's clock epoch, shared by its parts
    page_options.run_part = o.run_part - 1;
    page_options.run_parts = o.run_parts;
    page_options.parts = o.later_pages;
    page_options.parts_token = o.later_pages_token;
    if (router)
      page_options.route = [router](const control::ControlRequest& r, std::string_view line) { return router->route(r, line); };
    if (o.run_part > 1) {
      if (const char* token = std::getenv(kPartWebTokenVariable); token != nullptr) page_options.token = token;
      ::unsetenv(kPartWebTokenVariable);
    }
  }
  const std::string served = o.tap.empty() ? o.iface : o.tap;
  std::unique_ptr<web::WebServer> page;
  if (o.part_page) {
    page_options.address = {"127.0.0.1", 0};
    page = serve_web(page_options, *network, clock, counters, &faults, "run", served, [&waker] { waker.wake(); });
  } else {
    page = start_web(o.web, *network, clock, counters, &faults, "run", served, [&waker] { waker.wake(); }, false, &page_options);
  }
  // The fault control is polled with the telemetry's sampler when there is one; the page's
  // requests need it polled too. The status line's thread starts here.
  runtime::LoopService* base = telemetry ? &telemetry->service()
                               : control || faults.has_armed() || page ? static_cast<runtime::LoopService*>(&faults) : nullptr;
  telemetry::LoopServices with_page(base, page ? &page->service() : nullptr);
  runtime::LoopService* const services = status.wrap(page ? &with_page : base);
  // Real time, pinned and sliced last: the threads started above (control, telemetry, the page,
  // the status line) inherit none of it, so they neither run at the loop's priority nor share its CPU.
  if (o.rt_priority != 0) {
    const runtime::RealtimeResult rt = runtime::enter_realtime(o.rt_priority);
    if (rt.error != 0) {
      const bool denied = rt.error == EPERM || rt.error == EACCES;
      throw CliError(denied ? kExitNotPermitted : kExitFailure,
                     fmt::format("--rt-priority: {} failed: {}{}", rt.failed, std::strerror(rt.error),
                                 denied ? " (needs root or CAP_SYS_NICE and CAP_IPC_LOCK)" : ""));
    }
  }
  if (o.cpu >= 0) {
    if (const int err = runtime::pin_to_cpu(o.cpu); err != 0)
      throw CliError(kExitBadArguments, fmt::format("--cpu {}: {} (no such CPU, or not one this process may use)", o.cpu,
                                                    std::strerror(err)));
  }
  apply_time_slice(o);
  spdlog::info("serving {} slave(s) on {}: {} (hop delay {} ns{}{}); SIGINT/SIGTERM stops",
               o.drives.size(), where, fmt::join(o.drives, ", "), o.hop_delay,
               o.rt_priority != 0 ? fmt::format(", SCHED_FIFO {}", o.rt_priority) : "",
               o.batch_steps_us != 0 ? fmt::format(", control steps batched within {} us", o.batch_steps_us) : "");
  if (o.ready_fd >= 0) {  // the parent of --processes waits for this before it serves
    const std::string ready = page ? fmt::format("R{}", page->port()) : "R";
    if (::write(o.ready_fd, ready.data(), ready.size()) != static_cast<ssize_t>(ready.size()))
      spdlog::warn("--ready-fd {}: {}", o.ready_fd, std::strerror(errno));
    ::close(o.ready_fd);
  }
  try {
    link::Link& to_master = telemetry ? telemetry->link() : static_cast<link::Link&>(impaired);
    std::optional<runtime::OnwardLink> onward;
    if (onward_link) onward.emplace(to_master, *onward_link, *network, clock, counters);
    runtime::serve(*network, onward ? static_cast<link::Link&>(*onward) : to_master, clock, stop, counters, services);
  } catch (const link::LinkError& e) {  // the interface was removed while serving
    throw CliError(exit_code_for(e.kind()), e.what());
  }
  status.stop();  // its line ends before the summary
  spdlog::info("stopped: {} frames in, {} out, {} dropped, {} send failures", counters.frames_in.load(),
               counters.frames_out.load(), counters.dropped.load(), counters.send_failed.load());
  if (const std::uint64_t stalls = counters.stalls.count(); stalls > 0)
    spdlog::warn("host stalls: {}, longest {} (docs/reliability.md)", stalls, runtime::stall_ms(counters.stalls.longest()));
  else spdlog::info("host stalls: none");
  if (onward_link)
    spdlog::info("onward through {}: {} frames sent on, {} came back", o.next_iface, counters.onward.load(),
                 counters.returned.load());
  if (telemetry) spdlog::info("telemetry: {} samples published, {} dropped (publisher behind)", telemetry->published(), telemetry->dropped());
  for (const fault::Direction d : {fault::Direction::to_slaves, fault::Direction::to_master}) {
    const fault::WireImpairment::Counters& c = wire.counters(d);
    if (c.dropped + c.corrupted + c.duplicated + c.reordered == 0) continue;
    spdlog::info("wire faults {}: {} dropped, {} corrupted, {} duplicated, {} reordered",
                 d == fault::Direction::to_slaves ? "to the slaves" : "to the master", c.dropped, c.corrupted,
                 c.duplicated, c.reordered);
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Serve a line of drives on a network interface");
  CLI::Option* iface =
      cmd->add_option("--iface,-i", o->iface, "Interface the master is cabled to (raw socket)");
  CLI::Option* tap = cmd->add_option("--tap", o->tap, "Create/attach TAP device NAME and serve on it");
  iface->excludes(tap);
  cmd->add_option("--netns", o->netns,
                  "Open the interfaces (--iface, --tap, --next-iface) inside network namespace NAME (ip netns); the "
                  "control socket, telemetry and web page stay in this one (docs/cli.md)");
  CLI::Option* processes = cmd->add_option("--processes", o->processes,
                  "Cut the line into N consecutive parts, each served by its own process pinned to its own core, "
                  "chained over veth pairs made for the run (docs/scale-out.md); default 1")
      ->check(CLI::Range(1L, 64L));
  cmd->add_option("--ready-fd", o->ready_fd, "")->group("");  // a part of --processes tells its parent it serves
  cmd->add_option("--line-part", o->line_part, "")->group("");  // a part of --processes over a network file or ENI
  cmd->add_option("--slaves-before", o->slaves_before, "")->group("");  // a part of --processes: logs whole-line positions
  cmd->add_option("--run-part", o->run_part, "")->group("")->check(CLI::Range(1, 64));    // a part of --processes: its
  cmd->add_option("--run-parts", o->run_parts, "")->group("")->check(CLI::Range(1, 64));  // telemetry's fault ids
  cmd->add_option("--clock-origin", o->clock_origin, "")->group("");  // a part of --processes: one time base for telemetry
  cmd->add_flag("--part-page", o->part_page, "")->group("");  // a part of --processes: its page, which part 1's reads
  cmd->add_option("--next-iface", o->next_iface,
                  "The line goes on through interface NAME: out of the last slave's port 1 to whatever is cabled "
                  "there (another vdrive, real slaves) and back (docs/scale-out.md)");
  CLI::Option* drive = cmd->add_option("--drive,-d", o->drives,
                  "Product id of the next drive in cable order, or an ESI device FILE.xml[:PRODUCT[:REVISION]] (repeat)")
      ->take_all();
  CLI::Option* network_file = cmd->add_option("--network", o->network_file,
                  "Serve the network FILE describes (slaves, topology, aliases, plants, wires; docs/networks.md)");
  CLI::Option* eni = cmd->add_option("--eni", o->eni,
                  "Serve the network a master's ENI (EtherCATConfig XML) describes (docs/networks.md)");
  cmd->add_option("--esi-dir", o->esi_dirs, "With --eni: search DIR (recursively) for the slaves' ESI files (repeat)");
  drive->excludes(network_file);
  network_file->excludes(drive);
  eni->excludes(drive);
  eni->excludes(network_file);
  cmd->add_option("--plant", o->plants,
                  "N:FILE: slave N (cable order, 1 = first) moves the plant in FILE (docs/plant.md); repeat per slave")
      ->take_all();
  cmd->add_option("--hop-delay", o->hop_delay, "Delay per slave and direction in ns (default 500)")
      ->check(CLI::Range(Nanos{0}, Nanos{1'000'000'000}));
  cmd->add_option("--profile-dir", o->profile_dir,
                  "Load profiles from DIR/<id>/profile.yaml instead of the built-in ones");
  cmd->add_flag("--foe-strict", o->foe_strict,
               "FoE firmware download takes only a file named ECATFW__... in vdrive's image format, password 0 "
               "(the ETG SSC's checks; default: any file in Boot), docs/foe.md");
  CLI::Option* rt = cmd->add_option("--rt-priority", o->rt_priority,
                  "Serve with SCHED_FIFO priority 1..99 and locked memory (default: normal)")
      ->check(CLI::Range(1, 99));
  CLI::Option* slice = cmd->add_option("--slice-us", o->slice_us,
                  "Time slice of the serving thread in us (100..100000; Linux 6.12+): a frame or deadline waking it "
                  "preempts another task on its CPU at once. 0: the kernel's (default 100; skipped where the kernel "
                  "lacks it)")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            long us = -1;
            if (CLI::detail::lexical_cast(v, us) && (us == 0 || (us >= 100 && us <= 100'000))) return {};
            return "Value " + v + " is neither 0 (the kernel's slice) nor 100 to 100000";
          },
          "0 or 100..100000"))
      ->excludes(rt);
  CLI::Option* control = cmd->add_option("--control", o->control,
                  "Runtime fault control socket (default $XDG_RUNTIME_DIR/vdrive/IFACE.sock, /run/vdrive/IFACE.sock "
                  "for root, else /tmp/vdrive-UID/IFACE.sock); see vdrive fault");
  cmd->add_flag("--no-control", o->no_control, "Serve without the runtime control socket")->excludes(control);
  add_status_options(cmd, o->status);
  add_stall_option(cmd, o->stall_ms);
  cmd->add_option("--fault-seed", o->fault_seed, "Seed of the random wire faults (drop, corrupt, ...; default 1)");
  add_run_telemetry_options(cmd, o->telemetry);
  add_web_option(cmd, o->web);
  cmd->add_option("--busy-poll-us", o->busy_poll_us,
                  "Raw socket: spin up to US microseconds for the next frame before sleeping (default 0: sleep at once)")
      ->check(CLI::Range(0L, 1'000'000L));
  cmd->add_option("--batch-steps-us", o->batch_steps_us,
                  "Let each drive's control steps wait up to US microseconds for the next wake-up (a frame, SYNC0, a "
                  "request) and run there in a batch, each with its own instant, so the loop wakes for the bus and not "
                  "for every step (default 0: every step at its instant); docs/performance.md")
      ->check(CLI::Range(0L, 100'000L));
  cmd->add_option("--cpu", o->cpu, "Pin the serving thread to CPU N (default: not pinned)")->check(CLI::Range(0, 1023));
  CLI::Option* ring = cmd->add_flag("--no-rx-ring", o->no_rx_ring,
                "Raw socket: one recvfrom per frame instead of the receive ring shared with the kernel (PACKET_RX_RING, "
                "the default)")
      ->excludes(tap);
  // The ring became the default; the old flag still means it.
  cmd->add_flag("--rx-ring")
      ->description("Raw socket: take frames from the receive ring (the default)")
      ->excludes(tap)
      ->excludes(ring);
  cmd->add_flag("--no-qdisc-bypass", o->no_qdisc_bypass,
                "Send through the qdisc layer (so tc sees replies); default bypasses it");
  cmd->callback([o, slice, processes] {
    if (o->iface.empty() && o->tap.empty()) {
      throw CliError(kExitBadArguments, "run: one of --iface or --tap is required");
    }
    o->slice_given = slice->count() > 0;
    o->processes_given = processes->count() > 0;
    run(*o);
  });
}

}  // namespace vdrive::cli
