#pragma once
// A network from the master's ENI (EtherCATConfig XML, ETG.2100): the slaves the master was
// configured for, in its order, each matched to a device vdrive can serve, and their topology.
//
// Matching, for each <Slave><Info> (VendorId, ProductCode, RevisionNo):
//   1. a built-in (or --profile-dir) product with the same vendor and product code;
//   2. a device of an ESI file under the search directories (*.xml, recursively) with the same
//      vendor, product code and revision, else the same vendor and product code (nearest revision,
//      with a note);
//   3. none: served from the ENI's own description (identity, mailbox, process data, DC;
//      esi/eni_slave_device.hpp) as "FILE.xml#PHYSADDR", with a warning saying what was assumed;
//      refused, naming the slave, its identity and where vdrive looked, where the ENI says too
//      little (process data without a SyncManager address).
// Each slave's init commands (register and CoE) are tried on the device it is served as; those
// the device would refuse are warnings (eni_init_commands.hpp).
// Topology: <PreviousPort> names the slave before (PhysAddr) and its port (A-D = 0-3); the first
// slave hangs on the master. Every assumption is a note a user can read.
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/machine/network_file.hpp"

namespace vdrive::machine {

struct EniNetwork {
  NetworkFile network;               // slaves (names from the ENI), topology; no wires
  std::vector<std::uint16_t> station_addresses;  // <PhysAddr> per slave, as the master assigns them
  std::vector<std::string> notes;    // what was matched how, and what was assumed
  // The notes a user should look at: slaves served from the ENI alone, objects created for their
  // init commands, init commands the device would refuse. Each is in `notes` too.
  std::vector<std::string> warnings;
};

// Throws NetworkFileError ("<file>:<line>: <Element>: problem") for a malformed ENI or a slave no
// device matches and the ENI describes too little to serve.
EniNetwork read_eni(const std::string& path, const std::vector<std::string>& esi_dirs,
                    const std::string& profile_dir = {});
// The same for a document in memory; `file` names it in messages.
EniNetwork parse_eni(std::string_view text, const std::string& file, const std::vector<std::string>& esi_dirs,
                     const std::string& profile_dir = {});

// The network file (YAML) equivalent of `network`, for `vdrive network --from-eni`.
std::string to_network_yaml(const NetworkFile& network, const std::vector<std::string>& notes);

}  // namespace vdrive::machine
