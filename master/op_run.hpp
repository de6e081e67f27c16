#pragma once
// The whole way to Op and back, as `vdrive-master op` and `vdrive demo` run it:
//
//   scan -> Pre-Op -> process data (PDOs from CoE or SII, SM2/SM3, FMMUs)
//        -> [DC: delays, offsets, drift; 1C32h/1C33h sync type 2 + cycle time over CoE; SYNC0]
//        -> Safe-Op -> cyclic frames start -> Op (requested inside the cyclic frames)
//        -> N cycles in Op, wrong working counters counted -> Init.
//
// Steps that a slave does not support (no CoE answer for PDOs or 1C32h) fall back or are
// skipped with a note; failures that leave the line short of Op are reported in `error`.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "master/cyclic_task.hpp"

namespace vdrive::master {

class Master;

struct OpStatus {
  Nanos in_op = 0;                         // time since Op was first reached (cycles x cycle)
  const CyclicStats* stats = nullptr;
  std::uint64_t left_op = 0;
  std::uint64_t recoveries = 0;
  bool all_in_op = false;                  // in the last cycle
};

struct OpRunOptions {
  Nanos cycle = 1'000'000;
  Nanos reply_timeout = 0;                 // per cycle frame; 0: the cycle, at least 1 ms
  bool dc = true;
  std::uint64_t cycles = 1000;
  int drift_frames = 15000;
  std::int32_t sync0_shift = 0;
  Nanos mailbox_timeout = 500'000'000;
  std::uint64_t safeop_cycles = 100;       // cycles sent in Safe-Op before Op is requested
  Nanos op_timeout = 5'000'000'000;        // until every slave reports Op
  bool back_to_init = true;
  // In Op, as a PLC does: a slave that leaves Op (an AL error such as an SM watchdog after a stall
  // or an injected fault) is acknowledged and asked for Op again, every cycle until it is back.
  bool recover = false;
  // With `recover`: a line out of Op for longer than this did not come back (OpRunResult::overdue).
  Nanos recover_bound = 10'000'000'000;
  // Every `status_every` (0: never) of the cycles in Op, `status` gets the counters so far, so a
  // long run can be followed (and a fault's effect told from the counters before and after it).
  Nanos status_every = 0;
  std::function<void(const OpStatus&)> status;
  // The application: `preop` runs once in Pre-Op before the process data is configured (start-up
  // SDOs, PDO remapping); `outputs`/`inputs` run in every cycle from Safe-Op on, around the frame,
  // with the whole process image. The cycles in Op end early when `done` returns true.
  std::function<void(Master&)> preop;
  std::function<void(std::span<std::uint8_t> image)> outputs;
  std::function<void(std::span<std::uint8_t> image)> inputs;
  std::function<bool()> done;
};

struct OpRunResult {
  bool reached_op = false;
  CyclicStats stats;                       // of the cycles in Op
  ProcessImageLayout layout;
  std::uint16_t reference_station = 0;
  std::uint64_t sync0_start = 0;
  std::uint64_t left_op = 0;               // cycles whose AL status was not all-Op
  std::uint64_t recoveries = 0;            // times the line left Op and was asked back (recover)
  std::uint64_t overdue = 0;               // times it stayed out of Op beyond recover_bound
  Nanos longest_out_of_op = 0;             // the longest time the line was not all in Op
  std::vector<std::string> notes;          // fallbacks and skipped steps, one line each
  std::string error;                       // why Op was not reached (empty when it was)
  bool ok() const { return reached_op && stats.wrong_wkc == 0 && left_op == 0 && stats.cycles > 0; }
  // What a recovering run promises instead: faults may cost frames and Op, but the line came back
  // within the bound every time.
  bool recovered() const { return reached_op && stats.cycles > 0 && overdue == 0; }
};

// 1C32h/1C33h of slave `i`: DC SYNC0 synchronisation (type 2) and the cycle time, ETG.1020. What a
// slave refuses is noted, not thrown.
void write_dc_sync_parameters(Master& master, std::size_t i, Nanos cycle, std::vector<std::string>& notes);

// `progress` (optional) gets one line per step. The master must have scanned the line.
OpRunResult run_to_op(Master& master, const OpRunOptions& options,
                      const std::function<void(const std::string&)>& progress = {});

}  // namespace vdrive::master
