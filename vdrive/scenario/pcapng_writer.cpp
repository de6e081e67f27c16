#include "vdrive/scenario/pcapng_writer.hpp"

#include <array>
#include <stdexcept>
#include <vector>

namespace vdrive::scenario {
namespace {

// pcapng block types and options (IETF draft-ietf-opsawg-pcapng).
constexpr std::uint32_t kSectionHeader = 0x0A0D0D0A, kInterfaceDescription = 1, kEnhancedPacket = 6;
constexpr std::uint32_t kByteOrderMagic = 0x1A2B3C4D;
constexpr std::uint16_t kLinkTypeEthernet = 1;
constexpr std::uint16_t kOptEnd = 0, kIfTsresol = 9, kEpbFlags = 2;
constexpr std::uint32_t kInbound = 1, kOutbound = 2;

void put16(std::vector<std::uint8_t>& b, std::uint16_t v) { b.insert(b.end(), {std::uint8_t(v), std::uint8_t(v >> 8)}); }
void put32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}
void pad4(std::vector<std::uint8_t>& b) {
  while (b.size() % 4) b.push_back(0);
}

// Wraps a block body: type, total length, body, total length.
void block(std::ofstream& out, std::uint32_t type, std::vector<std::uint8_t> body) {
  pad4(body);
  std::vector<std::uint8_t> b;
  const auto total = static_cast<std::uint32_t>(body.size() + 12);
  put32(b, type);
  put32(b, total);
  b.insert(b.end(), body.begin(), body.end());
  put32(b, total);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

}  // namespace

PcapngWriter::PcapngWriter(const std::string& path) : out_(path, std::ios::binary | std::ios::trunc), path_(path) {
  if (!out_) throw std::runtime_error(path + ": cannot create the capture file");
  std::vector<std::uint8_t> shb;
  put32(shb, kByteOrderMagic);
  put16(shb, 1);
  put16(shb, 0);
  put32(shb, 0xFFFFFFFF);  // section length unknown
  put32(shb, 0xFFFFFFFF);
  block(out_, kSectionHeader, shb);
  std::vector<std::uint8_t> idb;
  put16(idb, kLinkTypeEthernet);
  put16(idb, 0);
  put32(idb, 0);           // no snap length limit
  put16(idb, kIfTsresol);
  put16(idb, 1);
  idb.push_back(9);        // 10^-9 s
  pad4(idb);
  put16(idb, kOptEnd);
  put16(idb, 0);
  block(out_, kInterfaceDescription, idb);
}

void PcapngWriter::write(std::span<const std::uint8_t> frame, Nanos time, bool to_master) {
  std::vector<std::uint8_t> epb;
  const auto t = static_cast<std::uint64_t>(time < 0 ? 0 : time);
  put32(epb, 0);  // interface 0
  put32(epb, static_cast<std::uint32_t>(t >> 32));
  put32(epb, static_cast<std::uint32_t>(t));
  put32(epb, static_cast<std::uint32_t>(frame.size()));
  put32(epb, static_cast<std::uint32_t>(frame.size()));
  epb.insert(epb.end(), frame.begin(), frame.end());
  pad4(epb);
  put16(epb, kEpbFlags);
  put16(epb, 4);
  put32(epb, to_master ? kInbound : kOutbound);
  put16(epb, kOptEnd);
  put16(epb, 0);
  block(out_, kEnhancedPacket, std::move(epb));
  ++frames_;
  if (!out_) throw std::runtime_error(path_ + ": writing the capture failed");
}

}  // namespace vdrive::scenario
