#pragma once
// Distributed-clock setup (ETG.1000.4 clause 9 / ET1100 datasheet section "Distributed Clocks"),
// in the order a master applies it:
//
//  1. delay measurement: BWR 0x0900 latches every slave's port receive times; per slave FPRD the
//     port times (0x0900-0x090F) and the port-0 receive time in local time (0x0918);
//  2. the line or tree and its propagation delays, from the port times and DL status of every
//     slave (dc_topology.hpp; on a line: delay(k) = delay(k-1) + (rt(k-1) - rt(k)) / 2, rt being
//     a slave's port-1 minus port-0 receive time);
//  3. offsets (0x0920) so that every slave's system time equals the reference clock's (the first
//     DC slave), which is set to the master's clock; delays written to 0x0928;
//  4. static drift compensation: many FRMW 0x0910 (reference reads, the others compare and slew);
//  5. SYNC0: 0x0981 = 0, start time = a whole number of cycles after (system time + lead) plus
//     shift, 0x0990 start, 0x09A0 cycle, 0x0981 = 0x03 (cyclic + SYNC0).
#include <cstdint>
#include <vector>

#include "common/clock.hpp"
#include "master/dc_topology.hpp"

namespace vdrive::master {

class Master;

struct DcOptions {
  int drift_frames = 1000;              // static drift compensation FRMWs (IgH/TwinCAT use ~15000)
};

struct DcResult {
  std::uint16_t reference_station = 0;  // 0: no slave supports DC
  std::size_t dc_slaves = 0;
};

// Step 1 and the topology of step 2: latches the receive times, fills Slave::parent/parent_port
// and returns the delays from the first slave; `local_times` (optional) gets each slave's 0x0918.
DcTopology measure_dc_topology(Master& master, std::vector<std::uint64_t>* local_times = nullptr);

// Steps 1-4 over every slave with DC (Slave::dc_supported). Fills Slave::dc_delay / dc_offset.
DcResult configure_dc(Master& master, const DcOptions& options = {});

// Step 5 for every DC slave: SYNC0 every `cycle` ns, first pulse `lead` ns or more from now,
// shifted by `shift`. Returns the start time written.
std::uint64_t activate_sync0(Master& master, std::uint32_t cycle, std::int32_t shift = 0, Nanos lead = 100'000'000);

}  // namespace vdrive::master
