#pragma once
// The fuzzers' input format: a sequence of records [flags(1) length(2, LE) bytes(length)], the
// length taken modulo 1600 and cut at the end of the input. Each record's bytes are copied into
// `buffer` (so the target may patch them), then `use(flags)` runs.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vdrive::fuzz {

template <typename Use>
void for_each_record(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>& buffer,
                     Use&& use) {
  std::size_t at = 0;
  while (at + 3 <= size) {
    const std::uint8_t flags = data[at];
    std::size_t len = static_cast<std::size_t>(data[at + 1] | (data[at + 2] << 8)) % 1600;
    at += 3;
    if (len > size - at) len = size - at;
    buffer.assign(data + at, data + at + len);
    at += len;
    use(flags);
  }
}

}  // namespace vdrive::fuzz
