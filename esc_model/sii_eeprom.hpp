#pragma once
// SII EEPROM emulation behind the ESC's EEPROM interface registers 0x0500-0x050F (ET1100 layout):
//   0x0500      EEPROM configuration (ECAT): bit0 offer control to PDI, bit1 force ECAT access
//   0x0501      PDI access state (PDI): bit0 PDI takes the interface (only while offered)
//   0x0502-03   control/status: bit0 ECAT write enable, bit6 8-byte reads, bit7 2-byte addressing,
//               bits 8-10 command (001 read, 010 write, 100 reload, 000 clear errors), bit11
//               checksum error, bit12 device info error, bit13 ack/command error, bit14 write
//               enable error, bit15 busy
//   0x0504-07   EEPROM word address;  0x0508-0F data (read: 4 words; write: word in 0x0508-09)
// The image is word-addressed, little-endian, as ETG.1000.6 / ETG.2010 lay it out; reads beyond it
// return 0xFFFF. A command keeps the interface busy for a short, fixed time (the I2C transfer);
// it completes in tick() or at the first access after that time. Writes from the side that does
// not own the interface are ignored; reads are served to both sides. Allocates nothing after
// construction.
#include <cstdint>
#include <span>
#include <vector>

#include "common/clock.hpp"

namespace vdrive::esc {

class SiiEeprom {
public:
  // Busy times of the emulated I2C transfers (shortened from a real EEPROM's ms write cycle so
  // that masters polling busy do not stall; the order of events is what matters).
  static constexpr Nanos kCommandOverhead = 2'000;   // start, device and address bytes
  static constexpr Nanos kReadTimePerWord = 3'000;   // per 16-bit word transferred
  static constexpr Nanos kWriteTime = 20'000;        // one word incl. the EEPROM write cycle
  static constexpr int kReadWords = 4;               // ET1100: 8-byte reads (0x0502 bit6 = 1)
  static constexpr int kConfigWords = 8;             // ESC configuration area, words 0-7

  explicit SiiEeprom(std::vector<std::uint8_t> image);

  // Power-on: interface registers to reset values, ESC configuration area (words 0-7) checked.
  void reset();

  // Register access; `offset` is relative to 0x0500 and stays within 0x0500-0x050F.
  void read(std::uint16_t offset, std::span<std::uint8_t> out, Nanos now, bool from_ecat);
  void write(std::uint16_t offset, std::span<const std::uint8_t> in, Nanos now, bool from_ecat);

  // Completes a command in progress once its busy time has passed.
  void tick(Nanos now);
  Nanos next_deadline() const;

  // ESC configuration area (words 0-7): valid when its CRC-8 (word 7 low byte) matches.
  bool config_area_valid() const;
  std::uint16_t word(std::size_t word_address) const;   // 0xFFFF beyond the image
  std::size_t size_bytes() const { return image_.size(); }
  // The whole image as it is now (EEPROM writes included), e.g. for persisting it.
  std::span<const std::uint8_t> image() const { return image_; }

  // True once after a power-on or a reload command finished with a valid configuration area:
  // the ESC then copies words 0-4 into 0x0140/0x0150/0x0982/0x0152/0x0012.
  bool take_reload_done();

  // Fault injection: the EEPROM stops acknowledging. Read, write and reload commands end with
  // the acknowledge error (0x0502 bit13) and change nothing; a reload (or the power-on load in
  // reset()) also reports the device information as not loaded (bit12) and loads nothing.
  // Kept across reset().
  void set_no_acknowledge(bool fail) { no_acknowledge_ = fail; }
  bool acknowledges() const { return !no_acknowledge_; }

private:
  enum Command : std::uint8_t { kNone = 0, kRead = 1, kWrite = 2, kReload = 4 };

  bool pdi_owns() const;
  void start(Command cmd, Nanos now, Nanos duration);
  void complete_if_due(Nanos now);
  void load_config_area();
  void sync_status_bytes();

  std::vector<std::uint8_t> image_;
  bool no_acknowledge_ = false;
  std::uint8_t regs_[16] = {};   // register image; 0x0502-03 rebuilt from status_ on read
  std::uint16_t status_ = 0;     // 0x0502-03
  Command running_ = kNone;
  Nanos busy_until_ = 0;
  bool reload_done_ = false;
};

// CRC-8 of the ESC configuration area (polynomial x^8+x^2+x+1, initial 0xFF, no reflection)
// over words 0-6; the result belongs in the low byte of word 7.
std::uint8_t sii_config_crc(std::span<const std::uint8_t> first_14_bytes);

}  // namespace vdrive::esc
