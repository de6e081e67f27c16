#include "master/value_text.hpp"

#include <fmt/format.h>

#include <charconv>
#include <stdexcept>

namespace vdrive::master {

namespace {
int width_of(std::string_view type) {
  if (type == "u8" || type == "i8") return 1;
  if (type == "u16" || type == "i16") return 2;
  if (type == "u32" || type == "i32") return 4;
  if (type == "u64" || type == "i64") return 8;
  return 0;
}
}  // namespace

const std::vector<std::string>& value_types() {
  static const std::vector<std::string> types{"u8", "u16", "u32", "u64", "i8", "i16", "i32", "i64", "string", "hex"};
  return types;
}

std::vector<std::uint8_t> encode_value(std::string_view type, std::string_view text) {
  if (type == "string") return {text.begin(), text.end()};
  if (type == "hex") {
    std::string digits;
    for (char c : text) {
      if (c == ' ' || c == ':') continue;
      digits.push_back(c);
    }
    if (digits.size() % 2) throw std::invalid_argument("hex value needs an even number of digits");
    std::vector<std::uint8_t> out;
    for (std::size_t i = 0; i < digits.size(); i += 2) {
      unsigned v = 0;
      const auto r = std::from_chars(digits.data() + i, digits.data() + i + 2, v, 16);
      if (r.ec != std::errc() || r.ptr != digits.data() + i + 2) throw std::invalid_argument("not a hex byte: " + digits.substr(i, 2));
      out.push_back(static_cast<std::uint8_t>(v));
    }
    return out;
  }
  const int width = width_of(type);
  if (width == 0) throw std::invalid_argument("unknown type '" + std::string(type) + "'");
  const bool is_signed = type[0] == 'i';
  std::string_view t = text;
  bool negative = false;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    negative = t[0] == '-';
    t.remove_prefix(1);
  }
  int base = 10;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    base = 16;
    t.remove_prefix(2);
  }
  std::uint64_t magnitude = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), magnitude, base);
  if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size()) {
    throw std::invalid_argument("'" + std::string(text) + "' is not a number");
  }
  const int bits = 8 * width;
  std::uint64_t raw = 0;
  if (is_signed) {
    const std::uint64_t limit = std::uint64_t{1} << (bits - 1);  // |min|
    if ((negative && magnitude > limit) || (!negative && magnitude > limit - 1)) {
      throw std::invalid_argument(fmt::format("{} is out of range for {}", text, type));
    }
    raw = negative ? ~magnitude + 1 : magnitude;
  } else {
    if (negative && magnitude != 0) throw std::invalid_argument(fmt::format("{} is negative, {} is unsigned", text, type));
    if (bits < 64 && magnitude >> bits) throw std::invalid_argument(fmt::format("{} is out of range for {}", text, type));
    raw = magnitude;
  }
  std::vector<std::uint8_t> out(static_cast<std::size_t>(width));
  for (int i = 0; i < width; ++i) out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(raw >> (8 * i));
  return out;
}

std::string decode_value(std::string_view type, const std::vector<std::uint8_t>& bytes) {
  if (type == "string") return {bytes.begin(), bytes.end()};
  int width = width_of(type);
  if (type == "hex" || width == 0 || bytes.size() > 8) {
    std::string s;
    for (std::size_t i = 0; i < bytes.size(); ++i) s += fmt::format("{}{:02X}", i ? " " : "", bytes[i]);
    return s;
  }
  if (static_cast<std::size_t>(width) != bytes.size()) width = static_cast<int>(bytes.size());
  std::uint64_t raw = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) raw |= static_cast<std::uint64_t>(bytes[i]) << (8 * i);
  if (width == 0) return "(empty)";
  const std::string hex = fmt::format("0x{:0{}X}", raw, 2 * width);
  if (type[0] == 'i' && width < 8 && (raw >> (8 * width - 1)) & 1) {
    const auto value = static_cast<std::int64_t>(raw | (~std::uint64_t{0} << (8 * width)));
    return fmt::format("{} ({})", hex, value);
  }
  if (type[0] == 'i') return fmt::format("{} ({})", hex, static_cast<std::int64_t>(raw));
  return fmt::format("{} ({})", hex, raw);
}

}  // namespace vdrive::master
