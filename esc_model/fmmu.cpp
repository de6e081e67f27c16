#include "esc_model/fmmu.hpp"

#include <algorithm>

#include "ethercat/little_endian.hpp"
#include "ethercat/registers.hpp"

namespace vdrive::esc {

namespace {
constexpr std::uint8_t kBitIndexMask = 0x07;
constexpr std::uint64_t kAddressSpaceBits = 0x10000ull * 8;  // physical addresses wrap at 64 KiB
}  // namespace

bool PhysicalPort::read_bytes(std::uint16_t address, std::span<std::uint8_t> out) {
  bool any = false;
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::uint8_t v = 0;
    if (read_byte(static_cast<std::uint16_t>(address + i), v)) {
      out[i] = v;
      any = true;
    }
  }
  return any;
}

bool PhysicalPort::write_bytes(std::uint16_t address, std::span<const std::uint8_t> in) {
  bool any = false;
  for (std::size_t i = 0; i < in.size(); ++i) {
    any = write_byte(static_cast<std::uint16_t>(address + i), in[i], 0xFF) || any;
  }
  return any;
}

Fmmu Fmmu::decode(std::span<const std::uint8_t, 16> r) {
  namespace f = ecat::reg::fmmu;
  Fmmu m;
  m.logical_start = ecat::get_le32(r, f::kLogicalStart);
  m.length = ecat::get_le16(r, f::kLength);
  m.logical_start_bit = r[f::kLogicalStartBit] & kBitIndexMask;
  m.logical_stop_bit = r[f::kLogicalStopBit] & kBitIndexMask;
  m.physical_start = ecat::get_le16(r, f::kPhysicalStart);
  m.physical_start_bit = r[f::kPhysicalStartBit] & kBitIndexMask;
  m.readable = (r[f::kType] & f::kTypeRead) != 0;
  m.writable = (r[f::kType] & f::kTypeWrite) != 0;
  m.active = (r[f::kActivate] & 0x01) != 0;
  return m;
}

bool Fmmu::overlap_bits(std::uint32_t logical, std::size_t length, std::uint64_t& first,
                        std::uint64_t& last) const {
  if (!active || this->length == 0 || length == 0) return false;
  const std::uint64_t win_first = static_cast<std::uint64_t>(logical_start) * 8 + logical_start_bit;
  const std::uint64_t win_last =
      (static_cast<std::uint64_t>(logical_start) + this->length - 1) * 8 + logical_stop_bit;
  if (win_last < win_first) return false;  // one-byte window with stop bit before start bit
  const std::uint64_t dg_first = static_cast<std::uint64_t>(logical) * 8;
  const std::uint64_t dg_last = (static_cast<std::uint64_t>(logical) + length) * 8 - 1;
  first = std::max(win_first, dg_first);
  last = std::min(win_last, dg_last);
  return first <= last;
}

std::uint64_t Fmmu::physical_bit(std::uint64_t logical_bit) const {
  const std::uint64_t win_first = static_cast<std::uint64_t>(logical_start) * 8 + logical_start_bit;
  const std::uint64_t base = static_cast<std::uint64_t>(physical_start) * 8 + physical_start_bit;
  return (base + (logical_bit - win_first)) % kAddressSpaceBits;
}

Fmmu::Transfer Fmmu::read(std::uint32_t logical, std::span<std::uint8_t> frame,
                          PhysicalPort& port) const {
  Transfer t;
  std::uint64_t first = 0;
  std::uint64_t last = 0;
  if (!readable || !overlap_bits(logical, frame.size(), first, last)) return t;
  t.matched = true;
  const std::uint64_t dg_first = static_cast<std::uint64_t>(logical) * 8;
  if (byte_aligned()) {
    const auto phys = static_cast<std::uint16_t>(physical_bit(first) / 8);
    t.done = port.read_bytes(phys, frame.subspan((first - dg_first) / 8, (last - first) / 8 + 1));
    return t;
  }
  std::int32_t current = -1;  // physical byte currently loaded
  std::uint8_t value = 0;
  bool ok = false;
  for (std::uint64_t bit = first; bit <= last; ++bit) {
    const std::uint64_t pbit = physical_bit(bit);
    const auto pbyte = static_cast<std::int32_t>(pbit / 8);
    if (pbyte != current) {
      current = pbyte;
      ok = port.read_byte(static_cast<std::uint16_t>(pbyte), value);
      t.done = t.done || ok;
    }
    if (!ok) continue;
    const auto mask = static_cast<std::uint8_t>(1u << (bit % 8));
    std::uint8_t& dst = frame[(bit - dg_first) / 8];
    if ((value >> (pbit % 8)) & 1u) {
      dst = static_cast<std::uint8_t>(dst | mask);
    } else {
      dst = static_cast<std::uint8_t>(dst & ~mask);
    }
  }
  return t;
}

bool Fmmu::written_bytes(std::uint32_t logical, std::size_t length, std::size_t& offset,
                         std::size_t& count) const {
  std::uint64_t first = 0;
  std::uint64_t last = 0;
  if (!writable || !overlap_bits(logical, length, first, last)) return false;
  const std::uint64_t dg_first = static_cast<std::uint64_t>(logical) * 8;
  offset = static_cast<std::size_t>((first - dg_first) / 8);
  count = static_cast<std::size_t>((last - dg_first) / 8) - offset + 1;
  return true;
}

Fmmu::Transfer Fmmu::write(std::uint32_t logical, std::span<const std::uint8_t> source,
                           PhysicalPort& port) const {
  Transfer t;
  std::uint64_t first = 0;
  std::uint64_t last = 0;
  if (!writable || !overlap_bits(logical, source.size(), first, last)) return t;
  t.matched = true;
  const std::uint64_t dg_first = static_cast<std::uint64_t>(logical) * 8;
  if (byte_aligned()) {
    const auto phys = static_cast<std::uint16_t>(physical_bit(first) / 8);
    t.done = port.write_bytes(phys, source.subspan((first - dg_first) / 8, (last - first) / 8 + 1));
    return t;
  }
  // Collect the bits that land in one physical byte and write them with one masked access.
  std::int32_t current = -1;
  std::uint8_t value = 0;
  std::uint8_t mask = 0;
  auto flush = [&] {
    if (current >= 0 && mask != 0) {
      t.done = port.write_byte(static_cast<std::uint16_t>(current), value, mask) || t.done;
    }
    value = 0;
    mask = 0;
  };
  for (std::uint64_t bit = first; bit <= last; ++bit) {
    const std::uint64_t pbit = physical_bit(bit);
    const auto pbyte = static_cast<std::int32_t>(pbit / 8);
    if (pbyte != current) {
      flush();
      current = pbyte;
    }
    const bool set = (source[(bit - dg_first) / 8] >> (bit % 8)) & 1u;
    const auto pmask = static_cast<std::uint8_t>(1u << (pbit % 8));
    mask = static_cast<std::uint8_t>(mask | pmask);
    if (set) value = static_cast<std::uint8_t>(value | pmask);
  }
  flush();
  return t;
}

}  // namespace vdrive::esc
