#pragma once
// EtherCAT datagram commands and wire layout (ETG.1000.4 clause 5).
#include <cstddef>
#include <cstdint>

namespace vdrive::master {

enum class Command : std::uint8_t {
  NOP = 0,
  APRD = 1, APWR = 2, APRW = 3,    // auto-increment (position) addressing
  FPRD = 4, FPWR = 5, FPRW = 6,    // configured station address
  BRD = 7, BWR = 8, BRW = 9,       // broadcast
  LRD = 10, LWR = 11, LRW = 12,    // logical (FMMU) addressing
  ARMW = 13, FRMW = 14,            // read at one slave, write to all following
};

constexpr std::size_t kEthernetHeaderSize = 14;
constexpr std::size_t kEtherCatHeaderSize = 2;     // length:11, reserved:1, type:4 (1 = PDU)
constexpr std::size_t kDatagramHeaderSize = 10;    // cmd, idx, address(4), len/flags(2), irq(2)
constexpr std::size_t kWkcSize = 2;
constexpr std::size_t kMaxEtherCatPayload = 1498;  // 1514 - 14 (Ethernet) - 2 (EtherCAT header)
constexpr std::uint16_t kDatagramLengthMask = 0x07FF;
constexpr std::uint16_t kDatagramMoreFollows = 0x8000;
constexpr std::uint16_t kDatagramCirculated = 0x4000;

}  // namespace vdrive::master
