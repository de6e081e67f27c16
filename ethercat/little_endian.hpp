#pragma once
// Little-endian loads and stores: EtherCAT puts every multi-byte field on the wire and in the ESC's
// registers least significant byte first. These sit on the frame path: constexpr, inline, no
// allocation. The byte shifts compile to single unaligned loads/stores on little-endian targets and
// stay correct on big-endian ones, with no memcpy or byte swap to get wrong.
#include <cstddef>
#include <cstdint>
#include <span>

namespace vdrive::ecat {

// ---- on raw pointers (p points at the first byte of the field) ------------------------------
constexpr std::uint16_t get_le16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
constexpr std::uint32_t get_le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
constexpr std::uint64_t get_le64(const std::uint8_t* p) {
  return static_cast<std::uint64_t>(get_le32(p)) | (static_cast<std::uint64_t>(get_le32(p + 4)) << 32);
}
// The first `bytes` bytes (at most 8; more are ignored) as an unsigned value, zero-extended:
// object values and DC registers of 1 to 8 bytes.
constexpr std::uint64_t get_le(const std::uint8_t* p, std::size_t bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = bytes < 8 ? bytes : 8; i-- > 0;) v = (v << 8) | p[i];
  return v;
}

constexpr void put_le16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
constexpr void put_le32(std::uint8_t* p, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
constexpr void put_le64(std::uint8_t* p, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
// The low `bytes` bytes of v; bytes past the eighth are written 0 (a 64-bit value zero-extended).
constexpr void put_le(std::uint8_t* p, std::uint64_t v, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i) p[i] = i < 8 ? static_cast<std::uint8_t>(v >> (8 * i)) : 0;
}

// ---- on spans, at a byte offset (the caller has checked the size) ---------------------------
constexpr std::uint16_t get_le16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}
constexpr std::uint32_t get_le32(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | (static_cast<std::uint32_t>(b[at + 1]) << 8) |
         (static_cast<std::uint32_t>(b[at + 2]) << 16) | (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
constexpr std::uint64_t get_le64(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint64_t>(get_le32(b, at)) |
         (static_cast<std::uint64_t>(get_le32(b, at + 4)) << 32);
}
// The whole span (at most its first 8 bytes) as an unsigned value, zero-extended.
constexpr std::uint64_t get_le(std::span<const std::uint8_t> b) {
  std::uint64_t v = 0;
  for (std::size_t i = b.size() < 8 ? b.size() : 8; i-- > 0;) v = (v << 8) | b[i];
  return v;
}

constexpr void put_le16(std::span<std::uint8_t> b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v);
  b[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
constexpr void put_le32(std::span<std::uint8_t> b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
constexpr void put_le64(std::span<std::uint8_t> b, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
// Fills the whole span with v, least significant byte first (bytes past the eighth 0).
constexpr void put_le(std::span<std::uint8_t> b, std::uint64_t v) {
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = i < 8 ? static_cast<std::uint8_t>(v >> (8 * i)) : 0;
}

}  // namespace vdrive::ecat
