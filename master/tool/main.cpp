// vdrive-master: the project's EtherCAT master as a command-line tool.
//
//   vdrive-master scan --iface IF [--state init|preop] [--json]
//   vdrive-master sdo-read  --iface IF --slave N --index 0x6041 [--sub 0] [--type u16] [--complete]
//   vdrive-master sdo-write --iface IF --slave N --index 0x6040 [--sub 0] [--type u16] [--complete] VALUE
//   vdrive-master od-list   --iface IF --slave N [--names]
//   vdrive-master foe-write --iface IF --slave N [--name NAME] FILE   (master/tool/foe_command.hpp)
//   vdrive-master foe-read  --iface IF --slave N --name NAME OUTPUT
//   vdrive-master op        --iface IF [--cycle-us 1000] [--dc] [--cycles N] [--drift-frames N]
//                           [--rt-priority N] [--reply-timeout-us N]
//                           [--sine [--amplitude U | --revolutions R] [--frequency HZ] [--seconds S]]
//                           [--recover [--recover-bound-ms MS]] [--status-every-ms MS]
//
// `op --sine` runs a CiA 402 program in Op (master/cia402_program.hpp): every drive is mapped for
// csp, enabled, and follows 607Ah = start + U (1 - cos(2 pi f t)); each drive's largest following error
// (60F4h) is printed against its window 6065h and exit status 1 reports a drive that faulted,
// never got enabled or left the window.
//
// `op --recover` runs as a PLC that rides out faults: a slave that leaves Op is acknowledged and
// asked back, a drive in Fault is reset and enabled again and moves on from where it stands. Each
// outage is printed as it starts and ends ("@T slave 1 @0x1001 MADLN15BE: out (603Fh FF18h)",
// "@T slave 1 @0x1001 MADLN15BE: enabled again after 412 ms", T the wall clock in seconds, so a
// script can match them with what it injected), each drive's count in its verdict; exit status 1
// when the line or a drive did not come back within --recover-bound-ms (default 10000).
// --status-every-ms prints the counters so far ("@T status: ...").
//
// --slave is the position scan prints (1 = first slave) or the station address (0x1001). Exit status, as vdrive's: 0
// success; 1 the line did not do what was asked (no reply, no slaves, a mailbox/SDO failure — an
// SDO abort prints its code and text —, a state not reached, wrong working counters, a drive that
// faulted); 2 a bad command line; 3 no such interface, or it is down; 4 not permitted. Errors are
// one line on stderr. Details: docs/master.md.
#include <CLI/CLI.hpp>
#include <sched.h>
#include <sys/mman.h>
#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <optional>
#include <time.h>
#include <string>

#include "master/al_state.hpp"
#include "master/cia402_program.hpp"
#include "master/dc.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "master/tool/foe_command.hpp"
#include "master/tool/slave_option.hpp"
#include "master/value_text.hpp"
#include "vdrive/link/raw_socket_link.hpp"

namespace {

// The exit codes of vdrive (vdrive/cli/exit_codes.hpp), so scripts treat both tools alike.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadArguments = 2;
constexpr int kExitNoInterface = 3;
constexpr int kExitNotPermitted = 4;

using vdrive::master::AlState;
using vdrive::master::Master;
using vdrive::master::Slave;

std::string hex32(std::uint32_t v) { return fmt::format("0x{:08X}", v); }

nlohmann::json to_json(const Slave& s) {
  nlohmann::json j;
  j["position"] = s.position + 1;  // from 1, as scan's lines and every vdrive command count
  j["station"] = fmt::format("0x{:04X}", s.station);
  j["vendor_id"] = hex32(s.info.vendor_id);
  j["product_code"] = hex32(s.info.product_code);
  j["revision"] = hex32(s.info.revision);
  j["serial"] = hex32(s.info.serial);
  j["name"] = s.info.name;
  j["order"] = s.info.order;
  j["group"] = s.info.group;
  j["mailbox"] = {{"rx_offset", s.info.mailbox_rx_offset}, {"rx_size", s.info.mailbox_rx_size},
                  {"tx_offset", s.info.mailbox_tx_offset}, {"tx_size", s.info.mailbox_tx_size},
                  {"protocols", fmt::format("0x{:04X}", s.info.mailbox_protocols)}};
  j["state"] = std::string(vdrive::master::to_string(s.state()));
  j["al_error"] = s.al.error;
  j["al_status_code"] = fmt::format("0x{:04X}", s.al.status_code);
  j["parent"] = s.position == 0 ? 0 : s.parent + 1;  // 0: the master
  j["parent_port"] = s.parent_port;
  j["delay_ns"] = s.dc_delay;
  return j;
}

int run_scan(const std::string& iface, const std::optional<AlState>& target, bool json) {
  vdrive::link::RawSocketLink link(iface);
  Master master(link);
  if (master.scan() == 0) {
    throw std::runtime_error("no EtherCAT slaves on " + iface + " (frames come back with working counter 0)");
  }
  // Where each slave hangs and how far: from one frame's receive times (DC slaves only).
  bool dc = false;
  for (const Slave& s : master.slaves()) dc |= s.dc_supported;
  if (dc) {
    const vdrive::master::DcTopology topology = vdrive::master::measure_dc_topology(master);
    for (std::size_t i = 0; i < master.slaves().size(); ++i) master.slaves()[i].dc_delay = topology.delay[i];
  }
  // scan() and request_state() leave each slave's AL status as last read.
  const bool reached = target ? master.request_state(*target) : true;

  if (json) {
    nlohmann::json out;
    out["interface"] = iface;
    out["slaves"] = nlohmann::json::array();
    for (const Slave& s : master.slaves()) out["slaves"].push_back(to_json(s));
    if (target) {
      out["requested_state"] = std::string(vdrive::master::to_string(*target));
      out["state_reached"] = reached;
    }
    std::puts(out.dump(2).c_str());
  } else {
    for (const Slave& s : master.slaves()) std::puts(vdrive::master::describe(s).c_str());
    if (dc) {
      std::puts("topology (from the receive times):");
      for (const Slave& s : master.slaves()) {
        if (s.position == 0) std::printf("  1 <- master\n");
        else std::printf("  %u <- %u port %d, %lld ns\n", s.position + 1u, s.parent + 1u, s.parent_port, static_cast<long long>(s.dc_delay));
      }
    }
  }
  if (!reached) {
    std::fprintf(stderr, "vdrive-master: not every slave reached %s\n",
                 std::string(vdrive::master::to_string(*target)).c_str());
    return kExitFailure;
  }
  return 0;
}

struct SdoArgs {
  std::string slave;
  std::string index_text;
  unsigned sub = 0;
  std::string type = "hex";
  bool complete = false;
  std::string value;
};

std::uint16_t parse_index(const std::string& text) {
  std::size_t used = 0;
  unsigned long v = 0;
  try {
    v = std::stoul(text, &used, 0);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || v > 0xFFFF) throw std::invalid_argument("--index '" + text + "' is not an object index (0x0000-0xFFFF)");
  return static_cast<std::uint16_t>(v);
}

// Scans, finds the slave --slave names and takes it to Pre-Op (the mailbox runs from there).
std::size_t open_preop(Master& master, const std::string& slave_text) {
  if (master.scan() == 0) throw std::runtime_error("no EtherCAT slaves on the interface");
  const std::size_t slave = vdrive::master::tool::resolve_slave(master, slave_text);
  if (!master.request_state(slave, AlState::PreOp)) {
    throw std::runtime_error(vdrive::master::label(master.slaves()[slave]) +
                             " did not reach Pre-Op: " + vdrive::master::describe(master.slaves()[slave]));
  }
  return slave;
}

int run_sdo(const std::string& iface, const SdoArgs& a, bool write) {
  const std::uint16_t index = parse_index(a.index_text);
  if (a.sub > 0xFF) throw std::invalid_argument("--sub must be 0..255");
  std::vector<std::uint8_t> bytes;
  if (write) bytes = vdrive::master::encode_value(a.type, a.value);  // before touching the line
  vdrive::link::RawSocketLink link(iface);
  Master master(link);
  const std::size_t slave = open_preop(master, a.slave);
  auto& sdo = master.sdo(slave);
  const auto sub = static_cast<std::uint8_t>(a.sub);
  if (write) {
    sdo.download(index, sub, bytes, a.complete);
    std::printf("%04X:%02X <- %s\n", index, sub, vdrive::master::decode_value(a.type, bytes).c_str());
  } else {
    const auto value = sdo.upload(index, sub, a.complete);
    std::printf("%04X:%02X = %s\n", index, sub, vdrive::master::decode_value(a.type, value).c_str());
  }
  return 0;
}

int run_od_list(const std::string& iface, const std::string& slave_text, bool names) {
  vdrive::link::RawSocketLink link(iface);
  Master master(link);
  const std::size_t slave = open_preop(master, slave_text);
  auto& sdo = master.sdo(slave);
  const auto list = sdo.od_list();
  std::printf("%zu objects\n", list.size());
  for (std::uint16_t index : list) {
    if (!names) {
      std::printf("%04X\n", index);
      continue;
    }
    const auto d = sdo.object_description(index);
    std::printf("%04X  %-6s max sub %3u  type 0x%04X  %s\n", index,
                d.object_code == 7 ? "VAR" : d.object_code == 8 ? "ARRAY" : d.object_code == 9 ? "RECORD" : "?",
                d.max_subindex, d.data_type, d.name.c_str());
  }
  return 0;
}

// Seconds since the epoch with milliseconds, as `date +%s.%3N` prints them: event lines carry it
// so that a script matches them with what it did (vdrive fault inject) at that time. Printed in
// the cycle (status lines, outages): a buffer on the stack, no allocation.
struct WallTime {
  char text[32];
  const char* c_str() const { return text; }
};
WallTime wall_time() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  WallTime w{};
  std::snprintf(w.text, sizeof(w.text), "@%lld.%03d", static_cast<long long>(ts.tv_sec), static_cast<int>(ts.tv_nsec / 1'000'000));
  return w;
}

// SCHED_FIFO and locked memory, so that a loaded host does not delay a cycle by milliseconds.
void enter_realtime(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  if (::sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    throw std::runtime_error(std::string("--rt-priority: sched_setscheduler failed: ") + std::strerror(errno));
  }
  if (::mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    throw std::runtime_error(std::string("--rt-priority: mlockall failed: ") + std::strerror(errno));
  }
}

int run_op(const std::string& iface, vdrive::master::OpRunOptions options, int rt_priority,
           const std::optional<vdrive::master::SineProgramOptions>& sine) {
  if (rt_priority != 0) enter_realtime(rt_priority);
  vdrive::link::RawSocketLink link(iface);
  Master master(link);
  if (master.scan() == 0) throw std::runtime_error("no EtherCAT slaves on " + iface);
  for (const Slave& s : master.slaves()) std::puts(vdrive::master::describe(s).c_str());
  std::optional<vdrive::master::SineProgram> program;
  if (sine) {
    program.emplace(*sine);
    program->attach(options);
    options.cycles = program->cycles_needed(options.cycle);
    if (options.recover) {
      // Printed in the cycle, but only when a drive's outage starts or ends: a fault, not a cycle.
      program->on_recovery([](const vdrive::master::DriveResult& r, vdrive::master::DriveRecovery::Event event) {
        using Event = vdrive::master::DriveRecovery::Event;
        const auto& d = r.recovery;
        const std::string who = vdrive::master::label(r);
        if (event == Event::lost)
          std::printf("%s %s: out (603Fh %04Xh)\n", wall_time().c_str(), who.c_str(), d.code());
        else if (event == Event::recovered)
          std::printf("%s %s: enabled again after %lld ms (603Fh %04Xh)\n", wall_time().c_str(), who.c_str(),
                      static_cast<long long>(d.last_duration() / 1'000'000), d.code());
        else if (event == Event::overdue)
          std::printf("%s %s: not enabled again within the bound (603Fh %04Xh)\n", wall_time().c_str(), who.c_str(),
                      d.code());
      });
    }
  }
  if (options.status_every > 0) {
    options.status = [&program](const vdrive::master::OpStatus& s) {
      std::printf("%s status: %llu cycles, %llu wrong, %llu lost, %llu not all in Op, line %s, %zu/%zu drives enabled\n",
                  wall_time().c_str(), static_cast<unsigned long long>(s.stats->cycles),
                  static_cast<unsigned long long>(s.stats->wrong_wkc), static_cast<unsigned long long>(s.stats->lost_frames),
                  static_cast<unsigned long long>(s.left_op), s.all_in_op ? "in Op" : "out of Op",
                  program ? program->enabled_now() : std::size_t{0}, program ? program->drives() : std::size_t{0});
    };
  }
  const bool recover = options.recover;
  bool in_op = false;  // after Op the lines are events: stamped with the wall clock
  const auto result = vdrive::master::run_to_op(master, options, [&](const std::string& line) {
    if (recover && in_op) std::printf("%s %s\n", wall_time().c_str(), line.c_str());
    else std::printf("%s\n", line.c_str());
    in_op = in_op || line == "Op";
  });
  for (const auto& note : result.notes) std::printf("note: %s\n", note.c_str());
  // Every drive's verdict, whatever else went wrong: a failed run shows what each drive did.
  bool drives_ok = true;
  if (program) {
    for (const auto& r : program->results()) {
      std::printf("%s\n", vdrive::master::describe(r).c_str());
      drives_ok = drives_ok && r.ok();
    }
  }
  if (!result.reached_op) {
    std::fprintf(stderr, "vdrive-master: %s\n", result.error.c_str());
    return kExitFailure;
  }
  std::printf("summary: %llu cycles of %lld us, working counter %u expected, %llu wrong, %llu lost, %llu not all in Op\n",
              static_cast<unsigned long long>(result.stats.cycles), static_cast<long long>(options.cycle / 1000),
              result.layout.expected_wkc, static_cast<unsigned long long>(result.stats.wrong_wkc),
              static_cast<unsigned long long>(result.stats.lost_frames), static_cast<unsigned long long>(result.left_op));
  if (recover) {
    std::printf("recovery: the line left Op %llu times, longest out %lld ms, %llu not back within %lld ms\n",
                static_cast<unsigned long long>(result.recoveries),
                static_cast<long long>(result.longest_out_of_op / 1'000'000),
                static_cast<unsigned long long>(result.overdue), static_cast<long long>(options.recover_bound / 1'000'000));
    if (!result.recovered()) {
      std::fprintf(stderr, "vdrive-master: the line did not come back to Op within %lld ms\n",
                   static_cast<long long>(options.recover_bound / 1'000'000));
      return kExitFailure;
    }
    return drives_ok ? kExitOk : kExitFailure;
  }
  if (!result.ok()) {
    std::fprintf(stderr, "vdrive-master: %llu wrong working counters in %llu cycles\n",
                 static_cast<unsigned long long>(result.stats.wrong_wkc), static_cast<unsigned long long>(result.stats.cycles));
    return kExitFailure;
  }
  return drives_ok ? kExitOk : kExitFailure;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vdrive-master: a small EtherCAT master (scan a line, SDOs, cyclic operation)"};
  app.require_subcommand(1);
  std::string iface;
  std::string state_text;
  bool json = false;
  CLI::App* scan = app.add_subcommand("scan", "Find the slaves on an interface and print their identities");
  scan->add_option("--iface,-i", iface, "Network interface the line is connected to")->required();
  // Safe-Op and Op need process data configured (PDO mapping, SM2/SM3, FMMUs) and, in Op, sent
  // every cycle, which is `op`'s work: scan stops at Pre-Op and says where to go instead.
  scan->add_option("--state,-s", state_text, "Bring every slave to this state: init or preop (Safe-Op and Op: use op)")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            std::string lower;
            for (const char c : v) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            if (lower == "init" || lower == "preop") return {};
            if (lower == "safeop" || lower == "op")
              return v + ": scan configures no process data, which Safe-Op and Op need; `vdrive-master op` takes the "
                         "line there (docs/master.md)";
            return v + " is not a state scan can request: init or preop";
          },
          "init|preop"));
  scan->add_flag("--json", json, "Print JSON instead of one line per slave");

  SdoArgs sdo_args;
  auto add_sdo_options = [&](CLI::App* cmd) {
    cmd->add_option("--iface,-i", iface, "Network interface the line is connected to")->required();
    vdrive::master::tool::add_slave_option(cmd, sdo_args.slave);
    cmd->add_option("--index", sdo_args.index_text, "Object index, e.g. 0x6040")->required();
    cmd->add_option("--sub", sdo_args.sub, "Subindex (default 0)");
    cmd->add_option("--type", sdo_args.type, "u8 u16 u32 u64 i8 i16 i32 i64 string hex (default hex)")
        ->check(CLI::IsMember(vdrive::master::value_types()));
    cmd->add_flag("--complete", sdo_args.complete, "Complete access (the whole object from --sub 0 or 1)");
  };
  CLI::App* sdo_read = app.add_subcommand("sdo-read", "Read an object entry with an SDO upload");
  add_sdo_options(sdo_read);
  CLI::App* sdo_write = app.add_subcommand("sdo-write", "Write an object entry with an SDO download");
  add_sdo_options(sdo_write);
  sdo_write->add_option("VALUE", sdo_args.value, "The value, in the form --type says")->required();

  std::string list_slave;
  bool names = false;
  CLI::App* od_list = app.add_subcommand("od-list", "List a slave's objects with SDO information");
  od_list->add_option("--iface,-i", iface, "Network interface the line is connected to")->required();
  vdrive::master::tool::add_slave_option(od_list, list_slave);
  od_list->add_flag("--names", names, "Also read every object's description (name, type)");

  vdrive::master::OpRunOptions op_options;
  long long cycle_us = 1000;
  bool dc = false;
  CLI::App* op = app.add_subcommand("op", "Take the line to Op and exchange process data every cycle");
  op->add_option("--iface,-i", iface, "Network interface the line is connected to")->required();
  op->add_option("--cycle-us", cycle_us, "Cycle time in microseconds (default 1000)")->check(CLI::Range(50, 1'000'000));
  op->add_flag("--dc", dc, "Distributed clocks: delays, offsets, drift compensation, SYNC0 at the cycle time");
  op->add_option("--cycles", op_options.cycles, "Cycles to run in Op (default 1000)")->check(CLI::Range(1ull, 100'000'000ull));
  int rt_priority = 0;
  op->add_option("--rt-priority", rt_priority, "Run with SCHED_FIFO priority N (1..99) and locked memory")
      ->check(CLI::Range(1, 99));
  long long timeout_us = 0;
  op->add_option("--reply-timeout-us", timeout_us, "Wait this long for a cycle's frame (default: the cycle, at least 1000)")
      ->check(CLI::Range(50, 1'000'000));
  op->add_option("--drift-frames", op_options.drift_frames, "Static drift compensation frames (default 15000)")
      ->check(CLI::Range(0, 1'000'000));
  bool sine = false;
  vdrive::master::SineProgramOptions sine_options;
  double sine_seconds = 2.0;
  op->add_flag("--sine", sine, "Enable every CiA 402 drive in csp and command a sine (see docs/master.md)");
  CLI::Option* amplitude =
      op->add_option("--amplitude", sine_options.amplitude, "Sine amplitude in user units (default: one motor revolution)")
          ->check(CLI::Range(0.0, 2e9));
  op->add_option("--revolutions", sine_options.revolutions, "Sine amplitude in motor revolutions of each drive (default 1)")
      ->check(CLI::Range(0.001, 1000.0))
      ->excludes(amplitude);
  op->add_option("--frequency", sine_options.frequency_hz, "Sine frequency in Hz (default 1)")->check(CLI::Range(0.001, 100.0));
  op->add_option("--seconds", sine_seconds, "How long the sine runs (default 2)")->check(CLI::Range(0.01, 3600.0));
  op->add_flag("--recover", op_options.recover,
               "Ride out faults as a PLC does: acknowledge AL errors and request Op again, reset and re-enable "
               "faulted drives; fail only when one does not come back within --recover-bound-ms");
  long long recover_bound_ms = 10000;
  op->add_option("--recover-bound-ms", recover_bound_ms, "With --recover: how long the line and each drive may stay out (default 10000)")
      ->check(CLI::Range(10, 3'600'000));
  long long status_every_ms = 0;
  op->add_option("--status-every-ms", status_every_ms, "Print the counters every MS in Op (default: never)")
      ->check(CLI::Range(10, 3'600'000));
  vdrive::master::tool::FoeCommand foe(app);  // foe-write, foe-read
  app.set_version_flag("--version", std::string("vdrive-master ") + VDRIVE_VERSION);
  app.footer(
      "Examples:\n"
      "  vdrive-master scan --iface m2m                         # the slaves, their identities and delays\n"
      "  vdrive-master scan --iface m2m --state preop --json\n"
      "  vdrive-master sdo-read --iface m2m --slave 1 --index 0x1018 --sub 1 --type u32\n"
      "  vdrive-master op --iface m2m --dc --cycle-us 1000 --cycles 10000 --rt-priority 70\n"
      "  vdrive-master op --iface m2m --dc --sine --revolutions 0.5\n"
      "  vdrive-master op --iface m2m --dc --sine --seconds 600 --recover --status-every-ms 1000\n"
      "Exit status (as vdrive's): 0 done, 1 the line did not do it (no reply, state not reached, wrong working\n"
      "counters, a drive faulted, an SDO abort), 2 a bad command line, 3 no such interface or it is down,\n"
      "4 not permitted (root or CAP_NET_RAW). Details: docs/master.md");
  // One line, as every other error of this tool.
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return std::string("vdrive-master: ") + e.what() + "\n"; });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, the version or the error
    return code == 0 ? kExitOk : kExitBadArguments;
  }

  try {
    if (*scan) {
      std::optional<AlState> target;
      if (!state_text.empty()) target = vdrive::master::parse_al_state(state_text);
      return run_scan(iface, target, json);
    }
    if (*sdo_read) return run_sdo(iface, sdo_args, false);
    if (*sdo_write) return run_sdo(iface, sdo_args, true);
    if (*od_list) return run_od_list(iface, list_slave, names);
    if (foe.selected()) return foe.run();
    op_options.cycle = cycle_us * 1000;
    op_options.dc = dc;
    op_options.reply_timeout = timeout_us * 1000;
    op_options.recover_bound = recover_bound_ms * 1'000'000;
    op_options.status_every = status_every_ms * 1'000'000;
    std::optional<vdrive::master::SineProgramOptions> sine_run;
    if (sine) {
      sine_options.cycle = op_options.cycle;
      sine_options.motion = static_cast<vdrive::Nanos>(sine_seconds * 1e9);
      sine_options.recover = op_options.recover;
      sine_options.recovery_bound = op_options.recover_bound;
      sine_run = sine_options;
    }
    return run_op(iface, op_options, rt_priority, sine_run);
  } catch (const vdrive::link::LinkError& e) {
    std::fprintf(stderr, "vdrive-master: %s\n", e.what());
    switch (e.kind()) {
      case vdrive::link::LinkError::Kind::NoInterface:
      case vdrive::link::LinkError::Kind::InterfaceDown: return kExitNoInterface;
      case vdrive::link::LinkError::Kind::NotPermitted: return kExitNotPermitted;
      case vdrive::link::LinkError::Kind::BadName: return kExitBadArguments;
      case vdrive::link::LinkError::Kind::System: break;
    }
    return kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vdrive-master: %s\n", e.what());
    return kExitFailure;
  }
}
