// Minimal placeholder; full EEPROM interface follows.
#include "esc_model/sii_eeprom.hpp"

#include <algorithm>

namespace vdrive::esc {

SiiEeprom::SiiEeprom(std::vector<std::uint8_t> image) : image_(std::move(image)) { reset(); }

void SiiEeprom::reset() {
  std::fill(std::begin(regs_), std::end(regs_), 0);
  regs_[2] = 0x40;
  busy_until_ = 0;
  reload_done_ = true;
}

void SiiEeprom::read(std::uint16_t offset, std::span<std::uint8_t> out, Nanos, bool) {
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = (offset + i < 16) ? regs_[offset + i] : 0;
}

void SiiEeprom::write(std::uint16_t, std::span<const std::uint8_t>, Nanos, bool) {}

void SiiEeprom::tick(Nanos) {}
Nanos SiiEeprom::next_deadline() const { return INT64_MAX; }

bool SiiEeprom::config_area_valid() const {
  if (image_.size() < 16) return false;
  return sii_config_crc(std::span(image_).first(14)) == image_[14];
}

std::uint16_t SiiEeprom::word(std::size_t a) const {
  if (2 * a + 1 >= image_.size()) return 0xFFFF;
  return static_cast<std::uint16_t>(image_[2 * a] | (image_[2 * a + 1] << 8));
}

bool SiiEeprom::take_reload_done() {
  const bool d = reload_done_;
  reload_done_ = false;
  return d;
}

std::uint8_t sii_config_crc(std::span<const std::uint8_t> data) {
  std::uint8_t crc = 0xFF;
  for (std::uint8_t b : data) {
    crc ^= b;
    for (int i = 0; i < 8; ++i) crc = (crc & 0x80) ? static_cast<std::uint8_t>((crc << 1) ^ 0x07) : static_cast<std::uint8_t>(crc << 1);
  }
  return crc;
}

}  // namespace vdrive::esc
