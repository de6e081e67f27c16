#pragma once
// Fieldbus Memory Management Unit: maps a window of the 4 GiB logical address space, with bit
// granularity, onto physical ESC memory for LRD/LWR/LRW.
//
// The window covers logical bits [start*8 + start_bit, (start+length-1)*8 + stop_bit] and maps
// them in order onto physical bits from physical_start*8 + physical_start_bit. Byte-aligned
// windows (start bit 0, stop bit 7, physical start bit 0) are the common case and take a fast
// path; anything else (e.g. one bit of SM1 status 0x080D into a logical bit) goes bit by bit.
// Physical accesses go through a PhysicalPort, i.e. the ESC's normal memory path, so register
// permissions and SyncManager semantics apply to logical accesses as well.
#include <cstddef>
#include <cstdint>
#include <span>

namespace vdrive::esc {

// The ESC memory path as the FMMU sees it (ECAT side). Returns false if the access was refused
// (e.g. by a SyncManager); then nothing was read or written.
class PhysicalPort {
public:
  virtual bool read_byte(std::uint16_t address, std::uint8_t& out) = 0;
  virtual bool write_byte(std::uint16_t address, std::uint8_t value, std::uint8_t mask) = 0;
  // A run of whole bytes from `address` on (wrapping at 64 KiB), as read_byte/write_byte byte by
  // byte would do it (which is what these defaults do); true if any byte was accepted.
  virtual bool read_bytes(std::uint16_t address, std::span<std::uint8_t> out);
  virtual bool write_bytes(std::uint16_t address, std::span<const std::uint8_t> in);

protected:
  ~PhysicalPort() = default;
};

struct Fmmu {
  std::uint32_t logical_start = 0;
  std::uint16_t length = 0;
  std::uint8_t logical_start_bit = 0;
  std::uint8_t logical_stop_bit = 7;
  std::uint16_t physical_start = 0;
  std::uint8_t physical_start_bit = 0;
  bool readable = false;
  bool writable = false;
  bool active = false;

  // Decodes the 16 register bytes 0x0600+16n .. +15.
  static Fmmu decode(std::span<const std::uint8_t, 16> regs);

  struct Transfer {
    bool matched = false;  // the window overlaps the datagram
    bool done = false;     // at least one mapped byte was accepted by the memory path
  };
  // Datagram at logical address `logical` with `frame` data. Reads replace the mapped bits of
  // `frame`; writes store the mapped bits of `source` (the data as it arrived, so that LRW writes
  // what the master sent even where a read FMMU overlaps).
  Transfer read(std::uint32_t logical, std::span<std::uint8_t> frame, PhysicalPort& port) const;
  Transfer write(std::uint32_t logical, std::span<const std::uint8_t> source,
                 PhysicalPort& port) const;
  // The bytes of a `length`-byte datagram at `logical` that write() takes from `source`, as
  // [offset, offset + count); false if it takes none.
  bool written_bytes(std::uint32_t logical, std::size_t length, std::size_t& offset, std::size_t& count) const;

private:
  bool byte_aligned() const {
    return logical_start_bit == 0 && logical_stop_bit == 7 && physical_start_bit == 0;
  }
  // Overlap of the window with a datagram, as inclusive logical bit numbers; false if none.
  bool overlap_bits(std::uint32_t logical, std::size_t length, std::uint64_t& first,
                    std::uint64_t& last) const;
  std::uint64_t physical_bit(std::uint64_t logical_bit) const;
};

}  // namespace vdrive::esc
