#pragma once
// A scenario as read from its YAML file (schema: docs/scenarios.md; loader: scenario_loader.hpp):
// the segment, the built-in master, a timeline of steps (actions and faults) scheduled by time or
// by event, and expectations checked on the drive side. Every element keeps the line it came from
// so reports can point at it.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/clock.hpp"
#include "plant/plant_description.hpp"
#include "vdrive/fault/fault_spec.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::scenario {

// What a step or an expectation can wait for. Events of a slave name it (1-based).
enum class EventKind : std::uint8_t {
  start,           // t = 0
  preop, safeop, op,  // every slave reports that AL state (first time)
  enabled,         // 6041h shows Operation enabled (first time)
  fault,           // 6041h bit 3 (Fault) rises
  target_reached,  // 6041h bit 10 rises after the slave's last set-point or motion step
  step,            // the named step has run
};

// A point in scenario time: `delay` after an event (`start` = an absolute time).
struct TimePoint {
  EventKind event = EventKind::start;
  int slave = 0;          // enabled, fault, target_reached
  std::string step;       // step
  Nanos delay = 0;
  int line = 0;
};

struct Condition {
  std::optional<std::int64_t> equals;
  std::optional<std::int64_t> mask;      // applied before equals
  std::optional<double> min, max;        // inclusive
  std::optional<double> near;            // with tolerance: |value - near| <= tolerance
  double tolerance = 0.0;
};

enum class AlTarget : std::uint8_t { init = 1, preop = 2, boot = 3, safeop = 4, op = 8 };

struct StateAction { int slave = 0; AlTarget state = AlTarget::op; };   // slave 0: all
struct SdoWriteAction { int slave = 0; std::uint16_t index = 0; std::uint8_t subindex = 0; std::int64_t value = 0; };
// Reads an object over CoE; with a condition, the value read is checked like an expectation
// (reported under the step's name).
struct SdoReadAction {
  int slave = 0;
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::optional<Condition> expect;
};
struct ControlwordAction { int slave = 0; std::uint16_t value = 0; };
struct ModeAction { int slave = 0; std::int8_t mode = 0; };
// Walks the power state machine to Operation enabled in `mode` through the cyclic controlword
// (fault reset, shutdown, switch on, enable operation), as a PLC's MC_Power does.
struct EnableAction { int slave = 0; std::int8_t mode = 8; };
struct DisableAction { int slave = 0; };
// A set-point in the RxPDO: position (607Ah), velocity (60FFh) or torque (6071h). In pp a new
// position is handed over with a 0->1 edge of 6040h bit 4 (bit 6 = relative when `relative`).
struct TargetAction {
  int slave = 0;
  std::optional<std::int32_t> position, velocity;
  std::optional<std::int16_t> torque;
  bool relative = false;
};
// csp: a motion the master interpolates each cycle. ramp: from the actual position to `position`
// at `velocity` (user units/s); sine: amplitude * (1 - cos(2 pi f t)) around the start for `duration`.
struct MotionAction {
  enum class Shape : std::uint8_t { ramp, sine } shape = Shape::ramp;
  int slave = 0;
  double position = 0.0, velocity = 0.0;     // ramp
  double amplitude = 0.0, frequency_hz = 1.0;  // sine
  Nanos duration = 0;
};
struct FaultAction { fault::FaultSpec fault; std::string id; };  // id: for clear_fault
struct ClearFaultAction { std::string id; };                       // "" = every active fault
struct AcknowledgeAction { int slave = 0; };                       // AL error acknowledge (0x0120 bit 4)
// Sets a signal: a named signal of the network file or a point ("di 0x6000:1", "x.home"), as
// network/signal_point.hpp reads them. A wire's target keeps it until the wire's next copy.
struct SignalAction { std::string signal; std::int64_t value = 0; };

using Action = std::variant<StateAction, SdoWriteAction, SdoReadAction, ControlwordAction, ModeAction, EnableAction, DisableAction,
                            TargetAction, MotionAction, FaultAction, ClearFaultAction, AcknowledgeAction, SignalAction>;

struct Step {
  std::string name;   // optional; events "step: NAME" refer to it
  TimePoint when;
  Action action;
  int line = 0;
};

// What an expectation measures (drive side: the slave's own objects and registers, so it holds
// for any master).
struct Probe {
  enum class Kind : std::uint8_t { object, al_state, al_status_code, esc_register, master_wrong_wkc, master_lost_frames, signal } kind = Kind::object;
  int slave = 0;
  std::uint16_t index = 0;      // object index, or the register address
  std::uint8_t subindex = 0;
  std::uint8_t size = 2;        // register bytes (1, 2 or 4), little-endian
  std::string signal;           // a named signal or a point, as SignalAction's
};


struct Expectation {
  std::string name;
  Probe probe;
  Condition condition;
  enum class Timing : std::uint8_t {
    at,       // checked once, at `when`
    by,       // must hold at some check in [from, when]
    always,   // must hold at every check in [from, until]
  } timing = Timing::at;
  TimePoint from;     // by / always: where checking starts (default: start)
  TimePoint when;     // at / by
  std::optional<TimePoint> until;  // always: default the end of the run
  int line = 0;
};

struct SlaveSpec {
  std::string product;                                   // profile id
  std::optional<plant::PlantDescription> plant;          // else the product's default plant
  int line = 0;
};

struct MasterSpec {
  Nanos cycle = 1'000'000;
  bool dc = true;
  AlTarget start_state = AlTarget::op;   // where the master takes the line at the start
  // SDO writes done in Pre-Op before the process data is configured (a PLC's start-up list).
  std::vector<SdoWriteAction> startup;
};

struct Scenario {
  std::string name;
  std::string description;
  std::string file;
  std::uint64_t seed = 1;
  Nanos duration = 0;                  // virtual time the run lasts
  Nanos trace_period = 0;              // 0: every cycle
  Nanos hop_delay = 500;
  std::vector<SlaveSpec> slaves;
  // segment.network: the network file's names, aliases, identities, topology, wires and signals
  // (plants are in `slaves`); empty for a segment of `slaves`.
  network::NetworkOptions network;
  std::string network_file;
  MasterSpec master;
  std::vector<Step> steps;
  std::vector<Expectation> expectations;
  // The run is meant to stop early with an error containing this text (e.g. a scan that meets a
  // broken EEPROM); then that stop is an expectation that held, and its absence one that failed.
  std::string expect_stop;
  int expect_stop_line = 0;
};

}  // namespace vdrive::scenario
