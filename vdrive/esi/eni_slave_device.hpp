#pragma once
// A device served from the ENI alone: a slave of the master's ENI that no built-in product and no
// ESI file describes, built as an EsiDevice from what the ENI says of it (identity, mailbox,
// process-data SyncManagers and PDOs, DC activation) and imported like any ESI device. Where the
// ENI is silent, ETG defaults are assumed and listed; where it says too little to serve the slave
// (process data without a SyncManager address) it is refused with an EsiError
// "<file>:<line>: <Element>: slave 'NAME' (...): what is missing".
//
// The objects behind its PDOs are synthesized as for a dictionary-less ESI device
// (esi_pdo_objects.hpp); an object a CoE init command downloads and the device would not have is
// created (type from the data's length, readable, writable in the states the commands run in), so
// the master's start-up succeeds.
//
// Named as "FILE.xml#PHYSADDR" (the slave's <PhysAddr>, decimal) wherever a device is named:
// network files, --drive, load_esi_device().
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/esi/eni_slave.hpp"
#include "vdrive/esi/esi_device.hpp"

namespace vdrive::esi {

struct EniSlaveDevice {
  EsiDevice device;
  std::vector<std::string> assumptions;  // what vdrive assumed where the ENI is silent
  std::vector<std::string> created;      // objects created for CoE init commands, one line each
};

EniSlaveDevice eni_slave_device(const EniSlave& slave);

// True for "FILE.xml#PHYSADDR" (any case of .xml).
bool is_eni_slave_reference(std::string_view name);
std::string eni_slave_reference(const std::string& eni_path, std::uint16_t phys_addr);
// Reads the ENI the reference names and builds its slave; EsiError when it has no such slave.
EniSlaveDevice load_eni_slave_device(std::string_view reference);

}  // namespace vdrive::esi
