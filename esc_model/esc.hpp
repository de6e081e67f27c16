#pragma once
// One EtherCAT Slave Controller (ET1100/ET1810-class): 64 KiB address space, registers
// 0x0000-0x0FFF, process RAM above, datagram engine, FMMUs, SyncManagers, SII EEPROM, DC, watchdogs.
//
// Two sides, as on silicon:
//  - ECAT side: process_frame() is called by the segment as a frame passes port 0 (forward).
//    It executes every datagram addressed to this ESC in place and bumps working counters.
//  - PDI side: pdi_read()/pdi_write() are the microcontroller's view (firmware). PDI accesses have
//    PDI write permissions and PDI side effects (e.g. reading AL Control clears its event, writing
//    the last byte of a mailbox SM buffer hands it to the master).
//
// Threading: single-threaded by design; the caller (one event loop) owns the ESC. No method
// allocates after construction.
//
// Implementation map: ethercat/registers.hpp (register map), datagram.* (frame layout), esc_impl.hpp
// (private state and how the .cpp files divide the work), fmmu.*, sync_manager.*, watchdog.*.
// Known simplifications: the circulating bit is handled only for a port 0 closed by DL control;
// SYNC0/1 always reach the AL event register (0x0220 bits 2/3) since the PDI has no SYNC pins;
// write protection (0x0020/0x0030), MII management and the EEPROM-emulation AL event (bit 5)
// are not modelled.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <memory>
#include <span>

#include "common/clock.hpp"
#include "esc_model/esc_config.hpp"
#include "esc_model/esc_faults.hpp"
#include "esc_model/frame_timing.hpp"

namespace vdrive::esc {

// Link state of a port as seen by the ESC (drives DL status 0x0110 and loop control).
struct PortLinks {
  bool port[4] = {false, false, false, false};
};

class Esc {
public:
  Esc(const EscConfig& config, const Clock& clock);
  ~Esc();
  Esc(const Esc&) = delete;
  Esc& operator=(const Esc&) = delete;

  // ---- ECAT side --------------------------------------------------------------------------
  // `pdu` is the EtherCAT frame payload: the 2-byte EtherCAT header followed by the datagrams.
  // Returns false (and counts an RX error) if the frame is malformed, i.e. a real ESC would have
  // destroyed it; the segment then drops the frame.
  bool process_frame(std::span<std::uint8_t> pdu, const FrameTiming& timing);
  // The same for a DLPDU frame the caller has checked: `datagrams` is dlpdu_datagrams(pdu), not 0.
  // ESCs change a frame's data, working counters and addresses, never its lengths, so a line
  // checks it once rather than in every ESC. Returns false if this ESC destroys it (circulating).
  bool process_checked_frame(std::span<std::uint8_t> pdu, std::size_t datagrams, const FrameTiming& timing);

  // A frame whose FCS is wrong arrived at `port` (0..3): nothing in it is executed. An ESC that
  // finds the error first counts an invalid frame (0x0300 + 2*port) and forwards the frame
  // marked; ESCs after it see the mark and count a forwarded RX error (0x0308 + port) instead,
  // so the master can locate the faulty cable. Counters saturate at 0xFF.
  void count_rx_error(int port, bool forwarded);

  // Physical link per port; set by the segment (topology, cable break). Updates DL status.
  void set_links(const PortLinks& links);
  // Whether the ESC sends a frame out of `port` (0..3): implemented in the port descriptor
  // (0x0007), link up and not closed by loop control (DL control 0x0100); otherwise the port is
  // looped back inside the ESC and the frame goes on to the next port in the order 0-3-1-2.
  bool port_forwards(int port) const;
  // A frame that left through `port` (1..3) with its time FrameTiming::kLater (the cable there
  // leads out of this process) came back at `now`: the DC receive-time latch of that frame, if it
  // wrote 0x0900, takes its time at that port now.
  void frame_returned(int port, Nanos now);

  // ---- PDI side (firmware) ----------------------------------------------------------------
  void pdi_read(std::uint16_t address, std::span<std::uint8_t> out);
  void pdi_write(std::uint16_t address, std::span<const std::uint8_t> in);
  // AL Event Request (0x0220) masked by AL Event Mask (0x0204): non-zero means "IRQ asserted".
  std::uint32_t pdi_irq() const;
  // The drive's microcontroller reading the SII EEPROM chip itself, as a firmware that checks its
  // SII at start-up does (A6B Err85.3): the word as stored now, EEPROM writes included, 0xFFFF
  // beyond the image; nothing when the EEPROM does not acknowledge (fault sii_error). Independent
  // of the 0x0500 ownership handshake and of 0x0502, which belong to the ESC's own interface.
  std::optional<std::uint16_t> pdi_eeprom_word(std::size_t word_address) const;

  // ---- time ---------------------------------------------------------------------------------
  // Called by the scheduler so the ESC can run time-based behaviour (watchdogs, SYNC0/1).
  void tick(Nanos now);
  // Next time tick() must be called (SYNC edge, watchdog expiry), or INT64_MAX.
  Nanos next_deadline() const;

  // Power-on reset: registers to their reset values, EEPROM reloaded into 0x0012 etc.
  void reset();

  // DC oscillator model (see dc_unit.hpp): drift in ppm and the local time at global time 0.
  // A property of the board, so reset() keeps it.
  void set_dc_model(double drift_ppm, Nanos start_offset);

  // Fault injection (esc_faults.hpp): takes effect at once, stays until changed.
  void set_faults(const EscFaults& faults);
  const EscFaults& faults() const;

  // Test and tooling access to the raw memory, without side effects. The SII (0x0500-0x050F)
  // and DC (0x0900-0x09FF) windows live in SiiEeprom/DcUnit and read 0 here.
  std::uint8_t peek(std::uint16_t address) const;
  // Two bytes as a little-endian word (AL Status, AL Status Code, counters).
  std::uint16_t peek_u16(std::uint16_t address) const {
    return static_cast<std::uint16_t>(peek(address) | peek(static_cast<std::uint16_t>(address + 1)) << 8);
  }

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdrive::esc
