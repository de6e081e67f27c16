#pragma once
// A CoE emergency message (ETG.1000.6, CoE service 1): 8 bytes after the CoE header. A6B:
// error code = 603Fh, error register = 1001h, data[0] = alarm sub code, data[1..4] = 0
// (L4643-L4842); all zero when the alarm is cleared (L4848-L4885).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ethercat/coe.hpp"
#include "ethercat/little_endian.hpp"

namespace vdrive::ecat::coe {

struct Emergency {
  std::uint16_t error_code = 0;
  std::uint8_t error_register = 0;
  std::array<std::uint8_t, 5> data{};

  static constexpr std::size_t kPayloadSize = kCoeHeaderSize + 8;

  // Writes the CoE payload (header with service 1, then the 8 bytes) into `out`.
  constexpr void encode(std::span<std::uint8_t> out) const {
    put_coe_header(out, Service::Emergency);
    put_le16(out, 2, error_code);
    out[4] = error_register;
    for (std::size_t i = 0; i < data.size(); ++i) out[5 + i] = data[i];
  }
  static constexpr Emergency decode(std::span<const std::uint8_t> payload) {
    Emergency e;
    e.error_code = get_le16(payload, 2);
    e.error_register = payload[4];
    for (std::size_t i = 0; i < e.data.size(); ++i) e.data[i] = payload[5 + i];
    return e;
  }
  friend constexpr bool operator==(const Emergency&, const Emergency&) = default;
};

}  // namespace vdrive::ecat::coe
