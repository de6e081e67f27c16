#pragma once
// What the runtime control channel carries between its thread and the event loop: a request
// (inject a fault, clear one or all, list them; read, set or list signals; which slave has a
// station address, asked by part 1 of `vdrive run --processes` of the others) and its reply. Parsed
// from and formatted to JSON lines by control_protocol.hpp; carried out by FaultService
// (fault_service.hpp), signals by signal_requests.hpp.
#include <cstdint>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/fault/fault_spec.hpp"

namespace vdrive::control {

struct ControlRequest {
  enum class Op : std::uint8_t { inject, clear, clear_all, list, signal_get, signal_set, signals, find_station, line_status };
  Op op = Op::list;
  fault::FaultSpec fault;  // inject
  int id = 0;              // clear
  std::string signal;      // signal_get, signal_set: a named signal or a point ("di 0x6000:1", "x.home")
  std::int64_t value = 0;  // signal_set
  std::uint16_t station = 0;  // find_station: a station address the master set
  std::uint64_t seq = 0;   // matches a reply to its request (set by FaultService::call)
};

struct FaultStatus {
  int id = 0;
  std::string kind;
  std::string description;  // fault::describe()
  Nanos elapsed = 0;
  Nanos remaining = -1;     // -1: until cleared
};

struct SignalStatus {
  std::string name;         // the network file's name, or the point as it was asked for
  std::string point;        // "di 0x6000:1", "x.home"
  std::string type;         // "BOOL", "I16", "connection" (signal_access.hpp)
  std::int64_t value = 0;
};

// What a status line shows of one slave (line_status: how part 1 of `run --processes` shows the
// later parts' slaves in its own).
struct SlaveState {
  std::uint16_t al_status = 0;       // 0x0130
  std::uint16_t al_status_code = 0;  // 0x0134
  std::uint32_t rx_errors = 0;       // the error counters 0x0300-0x030C, summed
};

struct ControlReply {
  // Why a request failed: the caller's mistake (exit 2), a peer that may not control this vdrive
  // (exit 4), or the server (exit 1).
  enum class Status : std::uint8_t { ok, bad_request, denied, failed };
  Status status = Status::ok;
  std::string error;
  int id = 0;                        // inject: the new fault's id (0 for one-shot faults)
  int cleared = 0;                   // clear_all: how many
  int slave = 0;                     // find_station: the slave (from 1) that has the address
  std::vector<FaultStatus> faults;   // list
  std::vector<SignalStatus> signals; // signal_get, signal_set (the value after the write), signals
  std::vector<SlaveState> states;    // line_status: every slave of this process, in cable order
  std::uint64_t seq = 0;
  bool ok() const { return status == Status::ok; }
};

inline ControlReply error_reply(ControlReply::Status status, std::string message) {
  ControlReply r;
  r.status = status;
  r.error = std::move(message);
  return r;
}

}  // namespace vdrive::control
