#pragma once
// Mailbox faults a test or scenario can give a slave (fault injection). Each is
// one-shot: MailboxModule counts it down (or clears it) as it acts, so faults() shows what is
// still to come. They act on every message the slave writes to SM1 (replies, mailbox errors,
// emergencies, a resend after a repeat request), not on what the master writes.
//
//   lose_replies       the next N messages are never written to SM1, as if their frame was lost
//                      on the wire; the slave still takes each as sent, so the master's repeat
//                      request (SM1 0x080E bit1) brings it back. A resend lost too counts as one
//                      more: with 2 the master's repeat fails as well and its request times out.
//   duplicate_replies  the next N messages are written twice, the second right after the master
//                      read the first, with the same mailbox counter (a repeated send); a master
//                      drops the copy by its counter.
//   toggle_error       the next SDO segment response (upload or download segment) carries the
//                      wrong toggle bit; the master aborts with 0x05030000.
//   abort_code         != 0: the next SDO request (not an abort) is answered with an SDO abort
//                      of this code for its index and subindex instead of being served; a
//                      transfer in progress ends.
#include <cstdint>

namespace vdrive::firmware::mailbox {

struct MailboxFaults {
  int lose_replies = 0;
  int duplicate_replies = 0;
  bool toggle_error = false;
  std::uint32_t abort_code = 0;
};

}  // namespace vdrive::firmware::mailbox
