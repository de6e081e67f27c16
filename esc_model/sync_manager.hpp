#pragma once
// One SyncManager channel: guards a process-RAM buffer so that master (ECAT) and
// microcontroller (PDI) exchange data consistently.
//
//  - Mailbox mode: one buffer. The writer fills it; writing the last byte makes it "full" and
//    raises the reader's interrupt. While full, writes are rejected. The reader may read only a
//    full buffer; reading the last byte empties it and raises the writer's interrupt. Rejected
//    accesses do not count for the working counter.
//  - Buffered (3-buffer) mode: the SM occupies 3 x length bytes; accesses to [start, start+len)
//    are redirected. The writer always gets a free buffer (never blocks); writing the last byte
//    makes it the newest. The reader opening the buffer (first byte) locks the newest buffer
//    until it reads the last byte, so it always sees one consistent snapshot.
//
// Access to a byte of the buffer opens the buffer even if it is not the first byte (the
// silicon expects the first byte to be accessed first; masters always do). The side that is
// not the writer cannot write the buffer; a writer-side read returns the buffer it is writing
// (or the newest) without changing any state.
#include <array>
#include <cstdint>
#include <span>

#include "esc_model/access_side.hpp"

namespace vdrive::esc {

class SyncManager {
public:
  // The SM's 8 register bytes (0x0800+8n .. +7).
  using Registers = std::span<const std::uint8_t, 8>;

  // Re-decodes the configuration. Enabling or disabling the SM resets its buffer state.
  void configure(Registers regs);
  // Buffer state back to power-on (empty, nothing written, nothing open).
  void reset_state();

  bool enabled() const { return enabled_; }
  bool covers(std::uint16_t address) const {
    return enabled_ && address >= start_ && address - start_ < length_;
  }
  bool mailbox() const { return mailbox_; }
  Side writer() const { return writer_; }
  bool watchdog_trigger() const { return watchdog_trigger_; }

  struct Result {
    bool ok = false;         // access performed (counts for the working counter)
    bool completed = false;  // the access wrote the last byte of the buffer
  };
  // A run of bytes [address, address + size) inside the window, as the same bytes accessed one by
  // one in ascending order: every byte is performed or none is. `memory` is the backed memory
  // (process RAM ends at memory.size()).
  Result read(Side side, std::uint16_t address, std::span<std::uint8_t> out,
              std::span<const std::uint8_t> memory);
  Result write(Side side, std::uint16_t address, std::span<const std::uint8_t> in,
               std::uint8_t mask, std::span<std::uint8_t> memory);
  // The window [start, end).
  std::uint16_t start() const { return start_; }
  std::uint32_t end() const { return std::uint32_t{start_} + length_; }

  // Status register (0x0805) as the silicon shows it.
  std::uint8_t status() const;
  // Interrupt towards the PDI (AL event bit 8+n) and towards ECAT (ECAT event bit 4+n).
  bool pdi_event() const { return enabled_ && al_event_enable_ && event_for(Side::Pdi); }
  bool ecat_event() const { return enabled_ && ecat_event_enable_ && event_for(Side::Ecat); }

private:
  static constexpr int kNone = -1;
  bool event_for(Side side) const;
  std::uint32_t buffer_address(int buffer, std::uint16_t address) const;
  int free_buffer() const;

  // configuration
  bool enabled_ = false;
  bool mailbox_ = false;
  Side writer_ = Side::Pdi;
  bool ecat_event_enable_ = false;
  bool al_event_enable_ = false;
  bool watchdog_trigger_ = false;
  std::uint16_t start_ = 0;
  std::uint16_t length_ = 0;
  // buffer state
  bool full_ = false;          // mailbox
  bool irq_write_ = false;     // buffer completely written (signalled to the reader)
  bool irq_read_ = false;      // buffer completely read (signalled to the writer)
  bool read_open_ = false;
  bool write_open_ = false;
  int newest_ = kNone;         // 3-buffer: last completely written buffer
  int read_buffer_ = 0;        // 3-buffer: buffer locked by the reader
  int write_buffer_ = 0;       // 3-buffer: buffer being written
};

}  // namespace vdrive::esc
