#include "master/sii.hpp"

#include <fmt/format.h>

#include "master/registers.hpp"

namespace vdrive::master {

SiiReader::SiiReader(Transport& transport, std::uint16_t station, Nanos busy_timeout)
    : transport_(transport), station_(station), busy_timeout_(busy_timeout) {}

void SiiReader::take_to_ecat() {
  // Force ECAT access (clears a PDI that holds the EEPROM), then stop offering it to the PDI.
  if (transport_.fpwr_value<std::uint8_t>(station_, reg::kEepromConfig, reg::kEepromForceEcat) != 1 ||
      transport_.fpwr_value<std::uint8_t>(station_, reg::kEepromConfig, 0) != 1) {
    throw SiiError(fmt::format("station 0x{:04X}: EEPROM interface 0x0500 not writable", station_));
  }
}

std::uint16_t SiiReader::wait_not_busy() {
  const Nanos deadline = transport_.clock().now() + busy_timeout_;
  for (;;) {
    auto status = transport_.fprd_value<std::uint16_t>(station_, reg::kEepromControl);
    if (!status) throw SiiError(fmt::format("station 0x{:04X}: no reply reading EEPROM status", station_));
    if (!(*status & reg::kEepromBusy)) return *status;
    if (transport_.clock().now() >= deadline) {
      throw SiiError(fmt::format("station 0x{:04X}: EEPROM busy for too long", station_));
    }
  }
}

std::vector<std::uint16_t> SiiReader::read_chunk(std::uint32_t word_address) {
  std::uint16_t status = wait_not_busy();
  if (status & reg::kEepromErrorBits) {
    // A previous command failed: writing a command of 0 clears the error bits.
    transport_.fpwr_value<std::uint16_t>(station_, reg::kEepromControl, 0);
    status = wait_not_busy();
  }
  // Command and address in one write (0x0502-0x0507), as masters do.
  std::array<std::uint8_t, 6> cmd{static_cast<std::uint8_t>(reg::kEepromCmdRead & 0xFF),
                                  static_cast<std::uint8_t>(reg::kEepromCmdRead >> 8),
                                  static_cast<std::uint8_t>(word_address),
                                  static_cast<std::uint8_t>(word_address >> 8),
                                  static_cast<std::uint8_t>(word_address >> 16),
                                  static_cast<std::uint8_t>(word_address >> 24)};
  if (transport_.fpwr(station_, reg::kEepromControl, cmd) != 1) {
    throw SiiError(fmt::format("station 0x{:04X}: EEPROM read command not accepted", station_));
  }
  status = wait_not_busy();
  if (status & reg::kEepromAckError) {
    throw SiiError(fmt::format("station 0x{:04X}: EEPROM read of word 0x{:04X} failed (status 0x{:04X})",
                               station_, word_address, status));
  }
  const std::size_t bytes = (status & reg::kEepromRead8Bytes) ? 8 : 4;
  std::array<std::uint8_t, 8> data{};
  if (transport_.fprd(station_, reg::kEepromData, std::span(data.data(), bytes)) != 1) {
    throw SiiError(fmt::format("station 0x{:04X}: no reply reading EEPROM data", station_));
  }
  std::vector<std::uint16_t> words;
  for (std::size_t i = 0; i < bytes; i += 2) {
    words.push_back(static_cast<std::uint16_t>(data[i] | (data[i + 1] << 8)));
  }
  return words;
}

std::vector<std::uint16_t> SiiReader::read_words(std::uint32_t word_address, std::size_t count) {
  std::vector<std::uint16_t> out;
  out.reserve(count + 4);
  while (out.size() < count) {
    auto chunk = read_chunk(word_address + static_cast<std::uint32_t>(out.size()));
    out.insert(out.end(), chunk.begin(), chunk.end());
  }
  out.resize(count);
  return out;
}

std::vector<std::uint16_t> SiiReader::read_image(std::size_t max_words) {
  std::vector<std::uint16_t> words = read_words(0, kSiiFirstCategoryWord);
  // Walk the category headers, reading each category as a whole.
  std::size_t at = kSiiFirstCategoryWord;
  while (at + 2 <= max_words) {
    auto header = read_words(static_cast<std::uint32_t>(at), 2);
    words.insert(words.end(), header.begin(), header.end());
    if (header[0] == sii_category::kEnd) break;
    const std::size_t size = header[1];
    const std::size_t take = std::min(size, max_words - (at + 2));
    if (take > 0) {
      auto body = read_words(static_cast<std::uint32_t>(at + 2), take);
      words.insert(words.end(), body.begin(), body.end());
    }
    at += 2 + size;
    if (take < size) break;
  }
  return words;
}

// ---- parsing ---------------------------------------------------------------------------------

namespace {

// Byte view of a category body, bounded by both its declared size and the image.
class Bytes {
public:
  Bytes(std::span<const std::uint16_t> words, std::size_t first_word, std::size_t word_count)
      : words_(words), first_(first_word),
        size_(2 * std::min(word_count, words.size() > first_word ? words.size() - first_word : 0)) {}
  std::size_t size() const { return size_; }
  std::uint8_t u8(std::size_t at) const {
    if (at >= size_) return 0;
    const std::uint16_t w = words_[first_ + at / 2];
    return static_cast<std::uint8_t>(at % 2 ? w >> 8 : w & 0xFF);
  }
  std::uint16_t u16(std::size_t at) const { return static_cast<std::uint16_t>(u8(at) | (u8(at + 1) << 8)); }

private:
  std::span<const std::uint16_t> words_;
  std::size_t first_;
  std::size_t size_;
};

std::uint32_t word32(std::span<const std::uint16_t> w, std::size_t at) {
  if (at + 1 >= w.size()) return 0;
  return static_cast<std::uint32_t>(w[at]) | (static_cast<std::uint32_t>(w[at + 1]) << 16);
}
std::uint16_t word16(std::span<const std::uint16_t> w, std::size_t at) { return at < w.size() ? w[at] : 0; }

std::string string_at(const SlaveInfo& info, std::uint8_t index) {
  // Strings are referenced 1-based; 0 means "no string".
  if (index == 0 || index > info.strings.size()) return {};
  return info.strings[index - 1];
}

void parse_strings(const Bytes& b, SlaveInfo& info) {
  const std::size_t count = b.u8(0);
  std::size_t at = 1;
  for (std::size_t i = 0; i < count && at < b.size(); ++i) {
    const std::size_t len = b.u8(at++);
    std::string s;
    for (std::size_t k = 0; k < len && at < b.size(); ++k) s.push_back(static_cast<char>(b.u8(at++)));
    info.strings.push_back(std::move(s));
  }
}

void parse_general(const Bytes& b, SlaveInfo& info) {
  info.has_general = true;
  info.group = string_at(info, b.u8(0));
  info.order = string_at(info, b.u8(2));
  info.name = string_at(info, b.u8(3));
  info.coe_details = b.u8(5);
  info.foe_details = b.u8(6);
  info.eoe_details = b.u8(7);
}

void parse_pdos(const Bytes& b, const SlaveInfo& info, std::vector<SiiPdo>& out) {
  std::size_t at = 0;
  while (at + 8 <= b.size()) {
    SiiPdo pdo;
    pdo.index = b.u16(at);
    const std::size_t entries = b.u8(at + 2);
    pdo.sync_manager = b.u8(at + 3);
    pdo.name = string_at(info, b.u8(at + 5));
    at += 8;
    for (std::size_t e = 0; e < entries && at + 8 <= b.size(); ++e, at += 8) {
      SiiPdoEntry entry;
      entry.index = b.u16(at);
      entry.subindex = b.u8(at + 2);
      entry.name = string_at(info, b.u8(at + 3));
      entry.data_type = b.u8(at + 4);
      entry.bit_length = b.u8(at + 5);
      pdo.entries.push_back(std::move(entry));
    }
    out.push_back(std::move(pdo));
  }
}

}  // namespace

SlaveInfo parse_sii(std::span<const std::uint16_t> w) {
  SlaveInfo info;
  info.alias = word16(w, 0x04);
  info.vendor_id = word32(w, 0x08);
  info.product_code = word32(w, 0x0A);
  info.revision = word32(w, 0x0C);
  info.serial = word32(w, 0x0E);
  info.boot_rx_offset = word16(w, 0x14);
  info.boot_rx_size = word16(w, 0x15);
  info.boot_tx_offset = word16(w, 0x16);
  info.boot_tx_size = word16(w, 0x17);
  info.mailbox_rx_offset = word16(w, 0x18);
  info.mailbox_rx_size = word16(w, 0x19);
  info.mailbox_tx_offset = word16(w, 0x1A);
  info.mailbox_tx_size = word16(w, 0x1B);
  info.mailbox_protocols = word16(w, 0x1C);
  info.eeprom_kbit = static_cast<std::uint16_t>(word16(w, 0x3E) + 1);

  // Strings first: General and PDO categories refer to them, whatever the category order.
  struct Cat { std::uint16_t type; std::size_t first, size; };
  std::vector<Cat> cats;
  for (std::size_t at = kSiiFirstCategoryWord; at + 1 < w.size();) {
    const std::uint16_t type = w[at];
    if (type == sii_category::kEnd) break;
    cats.push_back({type, at + 2, w[at + 1]});
    at += 2 + w[at + 1];
  }
  for (const Cat& c : cats) {
    if (c.type == sii_category::kStrings) parse_strings(Bytes(w, c.first, c.size), info);
  }
  for (const Cat& c : cats) {
    const Bytes b(w, c.first, c.size);
    switch (c.type) {
      case sii_category::kGeneral: parse_general(b, info); break;
      case sii_category::kFmmu:
        for (std::size_t i = 0; i < b.size(); ++i) info.fmmus.push_back(b.u8(i));
        break;
      case sii_category::kSyncManager:
        for (std::size_t at = 0; at + 8 <= b.size(); at += 8) {
          info.sync_managers.push_back({b.u16(at), b.u16(at + 2), b.u8(at + 4), b.u8(at + 6), b.u8(at + 7)});
        }
        break;
      case sii_category::kTxPdo: parse_pdos(b, info, info.tx_pdos); break;
      case sii_category::kRxPdo: parse_pdos(b, info, info.rx_pdos); break;
      default: break;
    }
  }
  return info;
}

}  // namespace vdrive::master
