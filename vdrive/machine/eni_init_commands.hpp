#pragma once
// The ENI's init commands for one slave, tried on the device vdrive serves for it, answered as that
// device would answer them, so a user learns before the master starts which ones it will see fail.
//
// CoE init commands (<Mailbox><CoE><InitCmds>): each SDO download or upload goes through the
// device's own SDO server (vdrive/firmware/coe/sdo_server.hpp) on a fresh copy of its object
// dictionary with its PDO write rules, in the state the master sends it in (IP, PS, SP, OP:
// Pre-Op; SO, OS: Safe-Op), in start-up order (IP, PS, SO, then the others as written), so a
// command sees what the commands before it wrote (1C12h:00 = 0, the entries, then the count).
// Register init commands (<InitCmds>): the mailbox SyncManagers they set up are checked as the
// device checks them at Init->PreOp, the DC activation they write as at PreOp->SafeOp.
//
// Each command the device would refuse is one note (the master sees the abort or the AL status
// code; it is not an error of the ENI): "<who>: CoE init command (line N, PS): download
// 1C12h:01h: the device answers abort 06090030h (value range of parameter exceeded)".
#include <string>
#include <vector>

#include "vdrive/esi/eni_slave.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::machine {

std::vector<std::string> check_init_commands(const esi::EniSlave& slave, const profile::ProductProfile& profile,
                                             const od::Dictionary& dictionary, const std::string& who);

}  // namespace vdrive::machine
