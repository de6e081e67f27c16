// EEPROM interface of an ET1100-class ESC. See sii_eeprom.hpp for the register layout.
#include "esc_model/sii_eeprom.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "ethercat/little_endian.hpp"
#include "ethercat/registers.hpp"
#include "ethercat/sii.hpp"

namespace vdrive::esc {
namespace {

// Offsets inside the SII window: regs_ holds 0x0500-0x050F.
constexpr std::uint16_t window(ecat::reg::Addr address) {
  return static_cast<std::uint16_t>(address - ecat::reg::kSiiFirst);
}
constexpr std::uint16_t kConfig = window(ecat::reg::kSiiConfig);
constexpr std::uint16_t kPdiAccess = window(ecat::reg::kSiiPdiAccess);
constexpr std::uint16_t kControlLow = window(ecat::reg::kSiiControlStatus);
constexpr std::uint16_t kControlHigh = kControlLow + 1;
constexpr std::uint16_t kAddress = window(ecat::reg::kSiiAddress);
constexpr std::uint16_t kData = window(ecat::reg::kSiiData);

using namespace ecat::reg::sii;

constexpr std::size_t k16KbitBytes = 2048;

bool covers(std::uint16_t offset, std::size_t len, std::uint16_t reg) {
  return reg >= offset && reg < offset + len;
}

}  // namespace

SiiEeprom::SiiEeprom(std::vector<std::uint8_t> image) : image_(std::move(image)) { reset(); }

void SiiEeprom::reset() {
  std::fill(std::begin(regs_), std::end(regs_), 0);
  status_ = kReads8Bytes;
  if (image_.size() > k16KbitBytes) status_ |= kTwoAddressBytes;
  running_ = kNone;
  busy_until_ = 0;
  reload_done_ = false;
  load_config_area();
}

void SiiEeprom::load_config_area() {
  status_ = static_cast<std::uint16_t>(status_ & ~(kChecksumError | kDeviceInfoError));
  if (no_acknowledge_) {
    // No answer from the EEPROM: nothing loaded, and the checksum could not even be checked.
    status_ |= kAckError | kDeviceInfoError;
    reload_done_ = false;
    return;
  }
  const bool ok = config_area_valid();
  // A bad checksum leaves the configuration unloaded: device information is not available.
  if (!ok) status_ |= kChecksumError | kDeviceInfoError;
  reload_done_ = ok;
}

bool SiiEeprom::pdi_owns() const {
  return (regs_[kConfig] & kOfferToPdi) && (regs_[kPdiAccess] & kPdiAccessing);
}

void SiiEeprom::sync_status_bytes() {
  ecat::put_le16(&regs_[kControlLow], status_);
}

void SiiEeprom::read(std::uint16_t offset, std::span<std::uint8_t> out, Nanos now, bool /*from_ecat*/) {
  complete_if_due(now);
  sync_status_bytes();
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::size_t reg = offset + i;
    out[i] = reg < sizeof(regs_) ? regs_[reg] : 0;
  }
}

void SiiEeprom::write(std::uint16_t offset, std::span<const std::uint8_t> in, Nanos now, bool from_ecat) {
  complete_if_due(now);
  const std::size_t len = in.size();
  auto byte_at = [&](std::uint16_t reg) { return in[reg - offset]; };

  // Ownership handshake registers.
  if (from_ecat && covers(offset, len, kConfig)) {
    regs_[kConfig] = byte_at(kConfig) & (kOfferToPdi | kForceEcat);
    // Forcing ECAT access or withdrawing the offer takes the interface back from the PDI.
    if ((regs_[kConfig] & kForceEcat) || !(regs_[kConfig] & kOfferToPdi)) regs_[kPdiAccess] = 0;
  }
  if (!from_ecat && covers(offset, len, kPdiAccess) && running_ == kNone) {
    const bool may_take = (regs_[kConfig] & kOfferToPdi) && !(regs_[kConfig] & kForceEcat);
    regs_[kPdiAccess] = may_take ? (byte_at(kPdiAccess) & kPdiAccessing) : 0;
  }

  const bool owner = from_ecat ? !pdi_owns() : pdi_owns();
  if (!owner || offset + len <= kControlLow) return;

  const bool command_written = covers(offset, len, kControlHigh);
  if (running_ != kNone) {
    // Busy: control, address and data writes are ignored; a command attempt is reported.
    if (command_written && (byte_at(kControlHigh) & 0x07) != 0) status_ |= kAckError;
    return;
  }

  for (std::uint16_t reg = std::max<std::uint16_t>(offset, kAddress); reg < offset + len && reg < sizeof(regs_); ++reg)
    regs_[reg] = byte_at(reg);

  // ECAT write enable counts only together with the command in the same access (the silicon
  // clears it at the next frame); it reads back as set while that write command runs.
  const bool write_enabled = from_ecat ? covers(offset, len, kControlLow) && (byte_at(kControlLow) & kWriteEnable)
                                       : true;
  if (!command_written) return;

  const std::uint8_t cmd = byte_at(kControlHigh) & 0x07;
  switch (cmd) {
    case kNone:
      status_ = static_cast<std::uint16_t>(status_ & ~(kAckError | kWriteEnableError));
      break;
    case kRead:
      start(kRead, now, kCommandOverhead + kReadWords * kReadTimePerWord);
      break;
    case kWrite:
      if (!write_enabled) {
        status_ = static_cast<std::uint16_t>((status_ & ~kAckError) | kWriteEnableError);
        break;
      }
      start(kWrite, now, kCommandOverhead + kWriteTime);
      if (from_ecat) status_ |= kWriteEnable;
      break;
    case kReload:
      start(kReload, now, kCommandOverhead + kConfigWords * kReadTimePerWord);
      break;
    default:
      status_ |= kAckError;  // invalid command
      break;
  }
}

void SiiEeprom::start(Command cmd, Nanos now, Nanos duration) {
  status_ = static_cast<std::uint16_t>(status_ & ~(kAckError | kWriteEnableError | kCommandMask));
  status_ |= kBusy | static_cast<std::uint16_t>(cmd << kCommandShift);
  running_ = cmd;
  busy_until_ = now + duration;
}

void SiiEeprom::complete_if_due(Nanos now) {
  if (running_ == kNone || now < busy_until_) return;
  const std::uint32_t address = ecat::get_le32(&regs_[kAddress]);
  const bool unanswered = no_acknowledge_ && running_ != kReload;  // reload: load_config_area
  if (unanswered) status_ |= kAckError;
  switch (unanswered ? kNone : running_) {
    case kRead:
      for (int w = 0; w < kReadWords; ++w) {
        const std::uint16_t value = word(static_cast<std::size_t>(address) + w);
        ecat::put_le16(&regs_[kData + 2 * w], value);
      }
      break;
    case kWrite: {
      const std::size_t byte = static_cast<std::size_t>(address) * 2;
      if (byte + 1 >= image_.size()) {
        status_ |= kAckError;  // no EEPROM cell answers at that address
        break;
      }
      image_[byte] = regs_[kData];
      image_[byte + 1] = regs_[kData + 1];
      break;
    }
    case kReload:
      load_config_area();
      break;
    case kNone:
      break;
  }
  running_ = kNone;
  status_ = static_cast<std::uint16_t>(status_ & ~(kBusy | kCommandMask | kWriteEnable));
}

void SiiEeprom::tick(Nanos now) { complete_if_due(now); }

Nanos SiiEeprom::next_deadline() const { return running_ != kNone ? busy_until_ : INT64_MAX; }

bool SiiEeprom::config_area_valid() const {
  std::uint8_t bytes[14];
  for (std::size_t w = 0; w < 7; ++w) {
    const std::uint16_t v = word(w);
    ecat::put_le16(&bytes[2 * w], v);
  }
  return sii_config_crc(bytes) == static_cast<std::uint8_t>(word(ecat::sii::kWordConfigChecksum));
}

std::uint16_t SiiEeprom::word(std::size_t word_address) const {
  const std::size_t byte = word_address * 2;
  if (word_address > image_.size() || byte + 1 >= image_.size()) return 0xFFFF;
  return ecat::get_le16(image_, byte);
}

bool SiiEeprom::take_reload_done() { return std::exchange(reload_done_, false); }

std::uint8_t sii_config_crc(std::span<const std::uint8_t> data) {
  // Table-free MSB-first CRC-8, polynomial 0x07, initial value 0xFF (ETG.2010).
  std::uint8_t crc = 0xFF;
  for (const std::uint8_t b : data) {
    crc ^= b;
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc & 0x80) ? static_cast<std::uint8_t>((crc << 1) ^ 0x07) : static_cast<std::uint8_t>(crc << 1);
  }
  return crc;
}

}  // namespace vdrive::esc
