#pragma once
// What the web page shows of one slave: what is fixed from start-up (SlaveInfo, read before the
// loop runs) and the ESC registers the loop copies for it (SlaveRegisters, plain values so the
// copy allocates nothing).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/clock.hpp"

namespace vdrive::network { class Network; }
namespace vdrive::profile { struct ProductProfile; struct AlarmSpec; }

namespace vdrive::web {

struct SlaveInfo {
  int position = 0;  // from 1, cable order
  std::string name;  // the network file's name, else empty
  std::string product, product_name;
  std::uint32_t vendor_id = 0, product_code = 0, revision = 0;
  bool drive = false;
  int parent = 0;       // the slave (from 1) whose port this one's port 0 is cabled to; 0: the master
  int parent_port = 0;  // that slave's port (1-3); 0 for the master
  const profile::ProductProfile* profile = nullptr;  // immutable while the network lives
};

struct SlaveRegisters {
  std::uint16_t station_address = 0, alias = 0;  // 0010h, 0012h
  std::uint16_t al_status = 0, al_status_code = 0;  // 0130h, 0134h
  std::array<std::uint8_t, 4> rx_errors{};   // per port: invalid frame counter 0300h + 2p
  std::array<std::uint8_t, 4> lost_links{};  // per port: 0310h + p
  bool dc_active = false;                    // 0981h: cyclic operation and SYNC0 on
  // The drive's newest active alarm (several alarms can share one 603Fh value, A6B 27.x all show
  // FF1Bh); a pointer into the immutable profile, or null.
  const profile::AlarmSpec* alarm = nullptr;
  // SDO aborts the slave answered a master with: how many so far, and the last (firmware's record).
  std::uint32_t sdo_aborts = 0;
  std::uint16_t abort_index = 0;
  std::uint8_t abort_subindex = 0;
  std::uint32_t abort_code = 0;
  std::int64_t system_time_difference = 0;   // 092Ch as signed ns
};

// Before the loop starts (reads the profiles).
std::vector<SlaveInfo> slave_infos(network::Network& network);
// Loop thread: copies every slave's registers into `out` (sized to the line, no allocation).
void read_registers(network::Network& network, std::vector<SlaveRegisters>& out);

}  // namespace vdrive::web
