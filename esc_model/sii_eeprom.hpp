#pragma once
// SII EEPROM emulation behind the ESC's EEPROM interface registers 0x0500-0x050F:
// configuration/ownership (ECAT vs PDI), control/status (read 4 or 8 bytes, write one word,
// reload, busy, checksum/ack/write-enable errors), address and data registers.
// The image is word-addressed, little-endian, as ETG.1000.6 / ETG.2010 lay it out.
#include <cstdint>
#include <span>
#include <vector>

#include "common/clock.hpp"

namespace vdrive::esc {

class SiiEeprom {
public:
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

  // True once after a power-on or a reload command finished: the ESC then copies words 0-4
  // into 0x0140/0x0150/0x0982/0x0152/0x0012.
  bool take_reload_done();

  // Fault injection hook (later issue): make reads fail with an acknowledge error.
  void set_read_error(bool fail) { inject_read_error_ = fail; }

private:
  std::vector<std::uint8_t> image_;
  bool inject_read_error_ = false;
  // Further private state is the implementation's (see sii_eeprom.cpp).
  std::uint8_t regs_[16] = {};
  Nanos busy_until_ = 0;
  bool reload_done_ = false;
};

// CRC-8 of the ESC configuration area (polynomial x^8+x^2+x+1, initial 0xFF) over words 0-6.
std::uint8_t sii_config_crc(std::span<const std::uint8_t> first_14_bytes);

}  // namespace vdrive::esc
