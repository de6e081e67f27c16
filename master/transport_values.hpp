#pragma once
// Template bodies of Transport's little-endian register helpers (included by transport.hpp).
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <type_traits>

namespace vdrive::master {

namespace detail {
template <class T> std::array<std::uint8_t, sizeof(T)> to_le(T value) {
  static_assert(std::is_integral_v<T>);
  std::array<std::uint8_t, sizeof(T)> out{};
  for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i));
  return out;
}
template <class T> T from_le(std::span<const std::uint8_t> in) {
  static_assert(std::is_integral_v<T>);
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(T) && i < in.size(); ++i) v |= static_cast<std::uint64_t>(in[i]) << (8 * i);
  return static_cast<T>(v);
}
}  // namespace detail

template <class T> Wkc Transport::fpwr_value(std::uint16_t station, std::uint16_t ado, T value) {
  auto bytes = detail::to_le(value);
  return fpwr(station, ado, bytes);
}
template <class T> Wkc Transport::bwr_value(std::uint16_t ado, T value) {
  auto bytes = detail::to_le(value);
  return bwr(ado, bytes);
}
template <class T> Wkc Transport::apwr_value(std::uint16_t position, std::uint16_t ado, T value) {
  auto bytes = detail::to_le(value);
  return apwr(position, ado, bytes);
}
template <class T> std::optional<T> Transport::fprd_value(std::uint16_t station, std::uint16_t ado) {
  std::array<std::uint8_t, sizeof(T)> bytes{};
  Wkc wkc = fprd(station, ado, bytes);
  if (!wkc || *wkc != 1) return std::nullopt;
  return detail::from_le<T>(bytes);
}

}  // namespace vdrive::master
