#pragma once
// Faults an ESC can be told to have (fault injection). The chip knows nothing of drives:
// each fault changes only what the silicon would do, and the firmware reacts on its own.
//
//   wkc_error            the datagram engine executes nothing addressed to this ESC and never
//                        bumps a working counter (frames still pass: auto-increment addresses are
//                        still counted up and event bits still ORed in), so the master sees a
//                        working counter short by this slave's share.
//   sii_error            the EEPROM no longer acknowledges: read, write and reload commands end
//                        with 0x0502 bit13 (missing acknowledge / command error); the data
//                        registers 0x0508+ keep their old contents; a reload or power-on load
//                        also sets bit12 (device information not loaded) and copies nothing.
//   sync_lost            the DC unit keeps its schedule but drives no SYNC0/SYNC1 pulse: no AL
//                        event bits 2/3, no 0x098E/0x098F status.
//   pd_watchdog_expired  when set, the process-data watchdog expires at once (0x0440 bit0 = 0,
//                        0x0442 + 1, AL event bit 6); while set, SM2 writes do not restart it.
//                        After clearing, the next watchdog-triggering SM2 write restarts it.
// Faults stay across Esc::reset() (they belong to the board); set_faults({}) clears them.
namespace vdrive::esc {

struct EscFaults {
  bool wkc_error = false;
  bool sii_error = false;
  bool sync_lost = false;
  bool pd_watchdog_expired = false;
};

}  // namespace vdrive::esc
