#include "master/op_run.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "master/dc.hpp"
#include "master/master.hpp"

namespace vdrive::master {

namespace {
constexpr std::uint16_t kSmOutputParameter = 0x1C32, kSmInputParameter = 0x1C33;
constexpr std::uint16_t kSyncTypeDcSync0 = 2;
constexpr std::uint8_t kAlAcknowledge = 0x10;  // AL control bit 4: Error Ind Ack (ETG.1000.6)

// A slave behind a broken cable does not answer: that is said, not thrown, so a recovering run
// goes on and asks again once the cable heals.
std::string al_summary(Master& master) {
  std::string text;
  for (std::size_t i = 0; i < master.slaves().size(); ++i) {
    try {
      master.read_al_status(i);
      text += "\n  " + describe(master.slaves()[i]);
    } catch (const std::exception& e) {
      text += fmt::format("\n  {}  0x{:04X}  no answer ({})", i + 1, master.slaves()[i].station, e.what());  // from 1, as describe()
    }
  }
  return text;
}
}  // namespace

// 1C32h/1C33h: synchronisation type (subindex 1) and cycle time (subindex 2), ETG.1020.
void write_dc_sync_parameters(Master& master, std::size_t i, Nanos cycle, std::vector<std::string>& notes) {
  const Slave& s = master.slaves()[i];
  if (!s.info.has_mailbox() || !(s.info.mailbox_protocols & mailbox_protocol::kCoE)) return;
  // 1C33h:02 follows 1C32h:02 on most drives (read-only there): only 1C32h gets the cycle time.
  for (std::uint16_t object : {kSmOutputParameter, kSmInputParameter}) {
    try {
      SdoClient& sdo = master.sdo(i);
      sdo.download_value<std::uint16_t>(object, 1, kSyncTypeDcSync0);
      if (object == kSmOutputParameter) sdo.download_value<std::uint32_t>(object, 2, static_cast<std::uint32_t>(cycle));
    } catch (const SdoAbort& e) {
      notes.push_back(fmt::format("slave {}: {:04X}h:{:02X} not written ({})", i + 1, object, e.subindex(), e.what()));
    } catch (const std::exception& e) {
      notes.push_back(fmt::format("slave {}: {:04X}h not written ({})", i + 1, object, e.what()));
    }
  }
}

OpRunResult run_to_op(Master& master, const OpRunOptions& options,
                      const std::function<void(const std::string&)>& progress) {
  OpRunResult result;
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  master.set_mailbox_timeout(options.mailbox_timeout);
  if (!master.request_state(AlState::PreOp)) {
    result.error = "not every slave reached Pre-Op:" + al_summary(master);
    return result;
  }
  say("Pre-Op");
  if (options.preop) options.preop(master);
  result.layout = configure_process_data(master, &result.notes);
  for (const Slave& s : master.slaves()) {
    const SlaveProcessData& pd = s.process_data;
    std::string pdos;
    for (const auto& p : pd.outputs) pdos += fmt::format(" {:04X}h", p.pdo);
    pdos += " /";
    for (const auto& p : pd.inputs) pdos += fmt::format(" {:04X}h", p.pdo);
    say(fmt::format("{}: {} output bytes at {}, {} input bytes at {}, PDOs{} (from {})", label(s), pd.output_bytes,
                    pd.output_logical, pd.input_bytes, pd.input_logical, pdos, pd.from_coe ? "CoE" : "SII"));
  }
  say(fmt::format("process image: {} output bytes, {} input bytes, expected LRW working counter {}",
                  result.layout.output_bytes, result.layout.input_bytes, result.layout.expected_wkc));

  if (options.dc) {
    const DcResult dc = configure_dc(master, DcOptions{options.drift_frames});
    result.reference_station = dc.reference_station;
    if (dc.dc_slaves == 0) {
      result.notes.push_back("no slave supports DC: running without");
    } else {
      for (std::size_t i = 0; i < master.slaves().size(); ++i) {
        if (master.slaves()[i].dc_supported) write_dc_sync_parameters(master, i, options.cycle, result.notes);
      }
      result.sync0_start = activate_sync0(master, static_cast<std::uint32_t>(options.cycle), options.sync0_shift);
      say(fmt::format("DC: reference 0x{:04X}, {} slaves, SYNC0 every {} ns from system time {}", dc.reference_station,
                      dc.dc_slaves, options.cycle, result.sync0_start));
    }
  }

  if (!master.request_state(AlState::SafeOp)) {
    result.error = "not every slave reached Safe-Op:" + al_summary(master);
    return result;
  }
  say("Safe-Op");
  CyclicTask task(master.transport(), result.layout, master.slaves().size(), options.cycle, result.reference_station);
  if (options.reply_timeout > 0) task.set_reply_timeout(options.reply_timeout);
  if (options.outputs) task.on_outputs(options.outputs);
  if (options.inputs) task.on_inputs(options.inputs);
  if (task.frames_per_cycle() > 1) {
    std::string pieces;
    for (const LrwPiece& p : task.pieces()) pieces += fmt::format(" {}+{} B (WKC {})", p.logical, p.bytes, p.expected_wkc);
    say(fmt::format("cyclic frames: {} per cycle, one LRW each:{}", task.frames_per_cycle(), pieces));
  }
  task.run(options.safeop_cycles);
  task.request_state(AlState::Op);
  const auto op_cycles = static_cast<std::uint64_t>(std::max<Nanos>(1, options.op_timeout / options.cycle));
  task.run(op_cycles, [&] { return task.all_in(AlState::Op); });
  if (!task.all_in(AlState::Op)) {
    result.error = "not every slave reached Op:" + al_summary(master);
    return result;
  }
  result.reached_op = true;
  say("Op");
  task.reset_stats();
  bool recovering = false;
  std::uint64_t cycle = 0, out_since = 0;
  bool out = false, out_overdue = false;
  const std::uint64_t status_cycles =
      options.status_every > 0 ? static_cast<std::uint64_t>(std::max<Nanos>(1, options.status_every / options.cycle)) : 0;
  const std::uint64_t bound_cycles = static_cast<std::uint64_t>(std::max<Nanos>(1, options.recover_bound / options.cycle));
  task.run(options.cycles, [&] {
    ++cycle;
    const bool all_in_op = task.all_in(AlState::Op);
    if (!all_in_op) {
      ++result.left_op;
      if (!out) {
        out = true;
        out_since = cycle;
        out_overdue = false;
      }
      if (!out_overdue && cycle - out_since > bound_cycles) {
        out_overdue = true;
        ++result.overdue;
        say(fmt::format("not back in Op within {} ms:{}", options.recover_bound / 1'000'000, al_summary(master)));
      }
      if (options.recover && !recovering) {
        // Op with the Error Ind Ack bit: the slave clears its error and goes back to Op.
        task.request_state(static_cast<AlState>(static_cast<std::uint8_t>(AlState::Op) | kAlAcknowledge));
        recovering = true;
        ++result.recoveries;
        say(fmt::format("left Op:{}; acknowledging and requesting Op", al_summary(master)));
      }
    } else {
      if (out) {
        result.longest_out_of_op = std::max(result.longest_out_of_op, static_cast<Nanos>(cycle - out_since) * options.cycle);
        out = false;
      }
      if (recovering) {
        task.request_state(static_cast<AlState>(0));  // back in Op: stop writing AL control
        recovering = false;
        say(fmt::format("back in Op after {} ms", static_cast<Nanos>(cycle - out_since) * options.cycle / 1'000'000));
      }
    }
    if (status_cycles > 0 && options.status && cycle % status_cycles == 0) {
      options.status(OpStatus{static_cast<Nanos>(cycle) * options.cycle, &task.stats(), result.left_op,
                              result.recoveries, all_in_op});
    }
    return options.done && options.done();
  });
  if (out) result.longest_out_of_op = std::max(result.longest_out_of_op, static_cast<Nanos>(cycle - out_since) * options.cycle);
  result.stats = task.stats();
  say(fmt::format("{} cycles in Op, {} wrong working counters, {} lost frames, worst lateness {} us (the latest a "
                  "cycle's frame left after its planned time)",
                  result.stats.cycles, result.stats.wrong_wkc, result.stats.lost_frames, result.stats.max_late / 1000));
  if (options.back_to_init) master.request_state(AlState::Init);
  return result;
}

}  // namespace vdrive::master
