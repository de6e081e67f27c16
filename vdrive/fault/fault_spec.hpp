#pragma once
// A fault as a scenario (or the command line) names it: its kind, from the catalogue below (one
// list for every layer, docs/faults.md), where it acts and its parameters. FaultInjector
// (fault_injector.hpp) carries it out; the reaction is the product's own, never scripted here.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "common/clock.hpp"

namespace vdrive::fault {

enum class Layer : std::uint8_t { wire, esc, mailbox, drive, plant };

enum class FaultKind : std::uint8_t {
  // wire: between the master and slave 1, or a cable of the line
  drop, corrupt, duplicate, reorder, delay, link_down,
  // esc: the chip of one slave
  wkc_error, sii_error, sync_lost, watchdog,
  // mailbox: the firmware's mailbox of one slave (one-shot: the next replies / request)
  lost_reply, duplicate_reply, toggle_error, sdo_abort,
  // drive: a cause the drive detects, raising the product's alarm for it
  encoder_error, overload, over_voltage, under_voltage, main_power_off, over_temperature, following_error, alarm,
  // plant: the machine the drive moves
  jam, collision, load_change, brake_failure,
};

struct FaultKindInfo {
  FaultKind kind;
  std::string_view name;     // as written in scenario files
  Layer layer;
  bool one_shot;             // acts once when injected (no duration, nothing to clear)
  std::string_view summary;  // one line for --help and docs
};

std::span<const FaultKindInfo> fault_catalogue();
const FaultKindInfo& info(FaultKind kind);
// Whether the kind acts at one slave (FaultSpec::slave or station): every layer but the wire's,
// and link_down (the cable at a slave's port); the other wire faults act on the master's cable.
bool acts_at_slave(FaultKind kind);
std::optional<FaultKind> fault_kind_from_name(std::string_view name);
std::string_view name(Layer layer);

enum class WireDirection : std::uint8_t { both, to_slaves, to_master };

struct FaultSpec {
  FaultKind kind = FaultKind::drop;
  // 1-based slave (the network's order) for esc, mailbox, drive and plant faults. link_down: the
  // cable at this slave's port `port`; port 0 is the cable into it (slave 1: from the master),
  // ports 1..3 lead to the slaves cabled behind it. Other wire faults: unused.
  int slave = 0;
  // Instead of `slave`: the slave with this configured station address (0x0010), which the master
  // sets at run time; the injector finds its position when the fault starts. 0: `slave` holds.
  std::uint16_t station = 0;
  int port = 0;                                // link_down only
  Nanos duration = 0;                          // 0: until cleared (or the end of the run)
  // wire
  WireDirection direction = WireDirection::both;
  double probability = 1.0;                    // drop, corrupt, duplicate, reorder: per frame
  Nanos delay = 0;                             // delay: every frame held this long
  // mailbox
  int count = 1;                               // lost_reply, duplicate_reply: how many replies
  std::uint32_t abort_code = 0x08000000;       // sdo_abort: the next SDO request gets this abort
  // drive
  std::string alarm;                           // alarm: a code of the product's alarms.yaml
  // plant
  double position = 0.0;                       // collision: the obstacle's load position
  double load_scale = 1.0;                     // load_change: inertia/mass factor
  double force = 0.0;                          // load_change: added external load (N or N m)
  double friction_scale = 1.0;                 // load_change: load-side friction factor (>= 0)
};

// "drop to_master p=0.5 for 100 ms" and the like, for logs and reports.
std::string describe(const FaultSpec& spec);

}  // namespace vdrive::fault
