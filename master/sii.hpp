#pragma once
// SII EEPROM access over EtherCAT (registers 0x0500-0x050F) and parsing of the image.
//
// Reading follows the ESC's protocol: take the EEPROM to the ECAT side (0x0500), wait until not
// busy, clear a pending error, write the read command with the word address (0x0502/0x0504),
// poll busy, then take 4 or 8 bytes from 0x0508 as 0x0502 bit 6 says.
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "master/slave_info.hpp"
#include "master/transport.hpp"

namespace vdrive::master {

class SiiError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class SiiReader {
public:
  SiiReader(Transport& transport, std::uint16_t station, Nanos busy_timeout = 100'000'000);

  // Gives the EEPROM interface to the master (force ECAT access, then release PDI offer).
  void take_to_ecat();
  // Reads 2 words starting at `word_address` (4 or 8 bytes as the ESC offers); throws SiiError
  // on no reply, busy timeout, or an error bit (ack / command error) in 0x0502.
  std::vector<std::uint16_t> read_chunk(std::uint32_t word_address);
  // Reads `count` words from `word_address`.
  std::vector<std::uint16_t> read_words(std::uint32_t word_address, std::size_t count);
  // Reads the fixed area (words 0-0x3F) and the category list up to the end marker 0xFFFF (or
  // `max_words`), returning the words read.
  std::vector<std::uint16_t> read_image(std::size_t max_words = 0x2000);

private:
  std::uint16_t wait_not_busy();
  Transport& transport_;
  std::uint16_t station_;
  Nanos busy_timeout_;
};

// Parses an SII image (words, as read) into a SlaveInfo. Tolerates truncated categories: what
// lies beyond the image is ignored, never read.
SlaveInfo parse_sii(std::span<const std::uint16_t> words);

// SII category types (ETG.1000.6 Table 19).
namespace sii_category {
constexpr std::uint16_t kNop = 0, kStrings = 10, kDataTypes = 20, kGeneral = 30, kFmmu = 40,
                        kSyncManager = 41, kTxPdo = 50, kRxPdo = 51, kDc = 60, kEnd = 0xFFFF;
}
constexpr std::size_t kSiiFirstCategoryWord = 0x40;

}  // namespace vdrive::master
