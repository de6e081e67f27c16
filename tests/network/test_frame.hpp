#pragma once
// An EtherCAT frame for the segment tests, built byte by byte from the ETG.1000.4 layout
// (independent of ethercat/datagram.hpp and the master library) and read back as a master would.
#include <cstdint>
#include <span>
#include <vector>

namespace vdrive::network::test_frames {

enum Cmd : std::uint8_t { APRD = 1, APWR = 2, FPRD = 4, FPWR = 5, BRD = 7, BWR = 8, FRMW = 14 };

// One EtherCAT frame: Ethernet header (optionally VLAN-tagged), EtherCAT header, datagrams.
class TestFrame {
public:
  explicit TestFrame(bool vlan = false) {
    bytes_ = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x11, 0x22, 0x33, 0x44, 0x55};
    if (vlan) bytes_.insert(bytes_.end(), {0x81, 0x00, 0x00, 0x05});
    bytes_.insert(bytes_.end(), {0x88, 0xA4, 0x00, 0x10});
    header_at_ = bytes_.size() - 2;
  }
  // Returns the byte offset of the datagram's data.
  std::size_t add(std::uint8_t cmd, std::uint16_t adp, std::uint16_t ado, std::vector<std::uint8_t> data) {
    if (last_ != 0) bytes_[last_ + 7] |= 0x80;  // "more datagrams follow" in the previous one
    last_ = bytes_.size();
    const auto len = static_cast<std::uint16_t>(data.size());
    bytes_.insert(bytes_.end(), {cmd, static_cast<std::uint8_t>(last_), static_cast<std::uint8_t>(adp),
                                 static_cast<std::uint8_t>(adp >> 8), static_cast<std::uint8_t>(ado),
                                 static_cast<std::uint8_t>(ado >> 8), static_cast<std::uint8_t>(len),
                                 static_cast<std::uint8_t>(len >> 8), 0, 0});
    const std::size_t at = bytes_.size();
    bytes_.insert(bytes_.end(), data.begin(), data.end());
    bytes_.insert(bytes_.end(), {0, 0});
    const auto total = static_cast<std::uint16_t>(bytes_.size() - header_at_ - 2);
    bytes_[header_at_] = static_cast<std::uint8_t>(total);
    bytes_[header_at_ + 1] = static_cast<std::uint8_t>(0x10 | (total >> 8));
    return at;
  }
  std::size_t read(std::uint8_t cmd, std::uint16_t adp, std::uint16_t ado, std::size_t n) {
    return add(cmd, adp, ado, std::vector<std::uint8_t>(n, 0));
  }
  std::span<std::uint8_t> span() { return bytes_; }
  std::uint64_t le(std::size_t at, int n) const {
    std::uint64_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = (v << 8) | bytes_[at + i];
    return v;
  }
  std::uint16_t wkc(std::size_t data_at, std::size_t n) const { return static_cast<std::uint16_t>(le(data_at + n, 2)); }
  std::uint16_t adp(std::size_t data_at) const { return static_cast<std::uint16_t>(le(data_at - 8, 2)); }
  std::uint8_t& operator[](std::size_t i) { return bytes_[i]; }

private:
  std::vector<std::uint8_t> bytes_;
  std::size_t header_at_ = 0;
  std::size_t last_ = 0;
};

inline std::vector<std::uint8_t> le_bytes(std::uint64_t v, int n) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) b[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
  return b;
}

}  // namespace vdrive::network::test_frames
