#pragma once
// A CoE emergency message (ETG.1000.6, CoE service 1): 8 bytes after the CoE header. A6B:
// error code = 603Fh, error register = 1001h, data[0] = alarm sub code, data[1..4] = 0
// (L4643-L4842); all zero when the alarm is cleared (L4848-L4885).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace vdrive::firmware::coe {

struct Emergency {
  std::uint16_t error_code = 0;
  std::uint8_t error_register = 0;
  std::array<std::uint8_t, 5> data{};

  static constexpr std::size_t kPayloadSize = 10;  // CoE header + 8 bytes

  // Writes the CoE payload (header with service 1, then the 8 bytes) into `out`.
  void encode(std::span<std::uint8_t> out) const {
    out[0] = 0x00;
    out[1] = 0x10;  // service 1 (emergency) in bits 15:12, number 0
    out[2] = static_cast<std::uint8_t>(error_code);
    out[3] = static_cast<std::uint8_t>(error_code >> 8);
    out[4] = error_register;
    for (std::size_t i = 0; i < data.size(); ++i) out[5 + i] = data[i];
  }
};

}  // namespace vdrive::firmware::coe
