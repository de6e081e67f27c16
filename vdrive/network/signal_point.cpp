#include "vdrive/network/signal_point.hpp"

#include <fmt/core.h>

#include <array>
#include <stdexcept>

#include "common/number_text.hpp"

namespace vdrive::network {
namespace {

constexpr std::array<std::string_view, 6> kConnectionNames = {"negative_limit", "positive_limit", "home",
                                                              "probe1",         "probe2",         "brake_release"};

std::size_t slave_of(std::string_view name, std::span<const std::string> names, std::string_view text) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  if (const auto v = parse_unsigned(name); v && *v >= 1 && *v <= names.size()) return static_cast<std::size_t>(*v - 1);
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument(fmt::format("'{}': no slave '{}' (names: {}; or a position 1-{})", text, name, known,
                                          names.size()));
}

}  // namespace

std::string_view connection_name(PlantConnection c) { return kConnectionNames.at(static_cast<std::size_t>(c)); }

std::optional<PlantConnection> connection_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kConnectionNames.size(); ++i)
    if (kConnectionNames[i] == name) return static_cast<PlantConnection>(i);
  return std::nullopt;
}

std::string connection_names() {
  std::string s;
  for (std::string_view n : kConnectionNames) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

SignalPoint parse_signal_point(std::string_view text, std::span<const std::string> slave_names) {
  SignalPoint p;
  const std::size_t space = text.find_last_of(' ');
  if (space == std::string_view::npos) {
    const std::size_t dot = text.find_last_of('.');
    if (dot == std::string_view::npos)
      throw std::invalid_argument(fmt::format(
          "'{}': expected SLAVE INDEX:SUBINDEX (e.g. 'do 0x7000:1') or SLAVE.CONNECTION (e.g. 'x.home')", text));
    p.slave = slave_of(text.substr(0, dot), slave_names, text);
    p.plant = connection_from_name(text.substr(dot + 1));
    if (!p.plant)
      throw std::invalid_argument(fmt::format("'{}': no plant connection '{}' (connections: {})", text,
                                              text.substr(dot + 1), connection_names()));
    return p;
  }
  p.slave = slave_of(text.substr(0, space), slave_names, text);
  const std::string_view entry = text.substr(space + 1);
  const std::size_t colon = entry.find(':');
  const auto index = colon == std::string_view::npos ? std::nullopt : parse_unsigned(entry.substr(0, colon));
  const auto sub = colon == std::string_view::npos ? std::nullopt : parse_unsigned(entry.substr(colon + 1));
  if (!index || *index > 0xFFFF || !sub || *sub > 0xFF)
    throw std::invalid_argument(fmt::format("'{}': the entry is INDEX:SUBINDEX, e.g. 0x7000:1", text));
  p.index = static_cast<std::uint16_t>(*index);
  p.subindex = static_cast<std::uint8_t>(*sub);
  return p;
}

std::string format_signal_point(const SignalPoint& point, std::span<const std::string> slave_names) {
  const std::string slave =
      point.slave < slave_names.size() ? slave_names[point.slave] : fmt::format("{}", point.slave + 1);
  if (point.plant) return fmt::format("{}.{}", slave, connection_name(*point.plant));
  return fmt::format("{} 0x{:04X}:{}", slave, point.index, point.subindex);
}

SignalPoint named_or_parsed_point(std::string_view text, std::span<const NamedSignal> signals,
                                  std::span<const std::string> slave_names) {
  for (const NamedSignal& s : signals)
    if (s.name == text) return s.point;
  try {
    return parse_signal_point(text, slave_names);
  } catch (const std::invalid_argument& e) {
    std::string names;
    for (const NamedSignal& s : signals) names += (names.empty() ? "" : ", ") + s.name;
    throw std::invalid_argument(fmt::format("no signal '{}' ({}) and not a point: {}", text,
                                            names.empty() ? "the network names none" : "signals: " + names, e.what()));
  }
}

}  // namespace vdrive::network
