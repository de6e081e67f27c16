#pragma once
// EtherCAT frame layout (ETG.1000.4): the 2-byte EtherCAT header and the datagrams behind it.
//
//   EtherCAT header (LE16): length bits 0-10 | reserved bit 11 | type bits 12-15 (1 = DLPDU)
//   Datagram: cmd(1) idx(1) address(4) len(LE16: length 0-10 | reserved 11-13 | circulating 14 |
//             more 15) irq(2) data(length) wkc(2)
//
// DatagramView is a non-owning view over one datagram inside a frame buffer; all accessors are
// little-endian and allocation-free.
#include <cstddef>
#include <cstdint>
#include <span>

#include "ethercat/little_endian.hpp"

namespace vdrive::ecat {

enum class Command : std::uint8_t {
  Nop = 0x00,
  Aprd = 0x01,
  Apwr = 0x02,
  Aprw = 0x03,
  Fprd = 0x04,
  Fpwr = 0x05,
  Fprw = 0x06,
  Brd = 0x07,
  Bwr = 0x08,
  Brw = 0x09,
  Lrd = 0x0A,
  Lwr = 0x0B,
  Lrw = 0x0C,
  Armw = 0x0D,
  Frmw = 0x0E,
};

inline constexpr std::size_t kEthercatHeaderSize = 2;
inline constexpr std::size_t kDatagramHeaderSize = 10;
inline constexpr std::size_t kWkcSize = 2;
inline constexpr std::uint8_t kFrameTypeDlpdu = 1;
inline constexpr std::uint16_t kMaxDatagramLength = 0x07FF;

struct EthercatHeader {
  std::uint16_t length = 0;  // bytes of datagrams following the header
  std::uint8_t type = 0;
};

inline constexpr std::uint16_t kHeaderLengthMask = 0x07FF;
inline constexpr int kHeaderTypeShift = 12;

inline EthercatHeader parse_ethercat_header(std::span<const std::uint8_t> pdu) {
  EthercatHeader h;
  if (pdu.size() < kEthercatHeaderSize) return h;
  const std::uint16_t raw = get_le16(pdu, 0);
  h.length = raw & kHeaderLengthMask;
  h.type = static_cast<std::uint8_t>(raw >> kHeaderTypeShift);
  return h;
}

class DatagramView {
public:
  // `bytes` starts at the datagram's command byte and covers header, data and WKC.
  explicit DatagramView(std::span<std::uint8_t> bytes) : b_(bytes) {}

  std::uint8_t command() const { return b_[0]; }
  std::uint8_t index() const { return b_[1]; }
  // Position/configured addressing: ADP (low word) and ADO (high word); logical: all 32 bits.
  std::uint16_t adp() const { return le16(2); }
  std::uint16_t ado() const { return le16(4); }
  std::uint32_t logical_address() const {
    return static_cast<std::uint32_t>(adp()) | (static_cast<std::uint32_t>(ado()) << 16);
  }
  std::uint16_t length() const { return le16(6) & kMaxDatagramLength; }
  bool circulating() const { return (le16(6) & kCirculatingBit) != 0; }
  bool more() const { return (le16(6) & kMoreBit) != 0; }
  std::uint16_t irq() const { return le16(8); }
  std::span<std::uint8_t> data() const { return b_.subspan(kDatagramHeaderSize, length()); }
  std::uint16_t wkc() const { return le16(kDatagramHeaderSize + length()); }

  void set_adp(std::uint16_t v) { put16(2, v); }
  void set_circulating(bool on) {
    const std::uint16_t v = le16(6);
    put16(6, on ? static_cast<std::uint16_t>(v | kCirculatingBit) : static_cast<std::uint16_t>(v & ~kCirculatingBit));
  }
  void set_irq(std::uint16_t v) { put16(8, v); }
  void set_wkc(std::uint16_t v) { put16(kDatagramHeaderSize + length(), v); }

  std::size_t size() const { return kDatagramHeaderSize + length() + kWkcSize; }

  static constexpr std::uint16_t kCirculatingBit = 1u << 14;
  static constexpr std::uint16_t kMoreBit = 1u << 15;

private:
  std::uint16_t le16(std::size_t at) const { return get_le16(b_, at); }
  void put16(std::size_t at, std::uint16_t v) { put_le16(b_, at, v); }
  std::span<std::uint8_t> b_;
};

// Checks that the header length fits the PDU and every datagram (followed through the "more"
// bit) lies inside the header length. Returns the number of datagrams, or 0 if malformed.
// Only meaningful for type-1 frames.
inline std::size_t validate_dlpdu(std::span<const std::uint8_t> pdu) {
  if (pdu.size() < kEthercatHeaderSize) return 0;
  const EthercatHeader h = parse_ethercat_header(pdu);
  // Bytes after the header length are Ethernet padding and are not looked at.
  if (h.length > pdu.size() - kEthercatHeaderSize) return 0;
  const std::size_t end = kEthercatHeaderSize + h.length;
  std::size_t at = kEthercatHeaderSize;
  std::size_t count = 0;
  for (;;) {
    if (end - at < kDatagramHeaderSize + kWkcSize) return 0;
    const std::uint16_t len_field = get_le16(pdu, at + 6);
    const std::size_t len = len_field & kMaxDatagramLength;
    const std::size_t size = kDatagramHeaderSize + len + kWkcSize;
    if (size > end - at) return 0;
    ++count;
    at += size;
    if ((len_field & DatagramView::kMoreBit) == 0) return count;
  }
}

// The datagrams of a well-formed DLPDU frame (type 1, validate_dlpdu); 0 for a frame too short
// for the header, of another type, or malformed.
inline std::size_t dlpdu_datagrams(std::span<const std::uint8_t> pdu) {
  if (pdu.size() < kEthercatHeaderSize || parse_ethercat_header(pdu).type != kFrameTypeDlpdu) return 0;
  return validate_dlpdu(pdu);
}

}  // namespace vdrive::ecat
