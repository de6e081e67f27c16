#include "esc_model/datagram.hpp"

namespace vdrive::esc {

namespace {
constexpr std::uint16_t kHeaderLengthMask = 0x07FF;
constexpr int kHeaderTypeShift = 12;
}  // namespace

EthercatHeader parse_ethercat_header(std::span<const std::uint8_t> pdu) {
  EthercatHeader h;
  if (pdu.size() < kEthercatHeaderSize) return h;
  const std::uint16_t raw = ecat::get_le16(pdu, 0);
  h.length = raw & kHeaderLengthMask;
  h.type = static_cast<std::uint8_t>(raw >> kHeaderTypeShift);
  return h;
}

std::uint32_t DatagramView::logical_address() const {
  return static_cast<std::uint32_t>(adp()) | (static_cast<std::uint32_t>(ado()) << 16);
}

void DatagramView::set_circulating(bool on) {
  std::uint16_t v = le16(6);
  v = on ? static_cast<std::uint16_t>(v | kCirculatingBit)
         : static_cast<std::uint16_t>(v & ~kCirculatingBit);
  put16(6, v);
}

std::size_t dlpdu_datagrams(std::span<const std::uint8_t> pdu) {
  if (pdu.size() < kEthercatHeaderSize || parse_ethercat_header(pdu).type != kFrameTypeDlpdu) return 0;
  return validate_dlpdu(pdu);
}

std::size_t validate_dlpdu(std::span<const std::uint8_t> pdu) {
  if (pdu.size() < kEthercatHeaderSize) return 0;
  const EthercatHeader h = parse_ethercat_header(pdu);
  // Bytes after the header length are Ethernet padding and are not looked at.
  if (h.length > pdu.size() - kEthercatHeaderSize) return 0;
  const std::size_t end = kEthercatHeaderSize + h.length;
  std::size_t at = kEthercatHeaderSize;
  std::size_t count = 0;
  for (;;) {
    if (end - at < kDatagramHeaderSize + kWkcSize) return 0;
    const std::uint16_t len_field = ecat::get_le16(pdu, at + 6);
    const std::size_t len = len_field & kMaxDatagramLength;
    const std::size_t size = kDatagramHeaderSize + len + kWkcSize;
    if (size > end - at) return 0;
    ++count;
    at += size;
    if ((len_field & DatagramView::kMoreBit) == 0) return count;
  }
}

}  // namespace vdrive::esc
